#include "scene/media/homogeneous_medium.h"

#include <cmath>

namespace rr {

namespace {

// e^{−σ d} for σ ≥ 0 and d ∈ [0, ∞], with e^{−0·∞} = 1 (0·∞ would be NaN).
double attenuation(double sigma, double distance) {
    return sigma > 0 ? std::exp(-sigma * distance) : 1.0;
}

}  // namespace

HomogeneousMedium::HomogeneousMedium(const Rgb& sigmaA, const Rgb& sigmaS,
                                     std::unique_ptr<PhaseFunction> phase)
    : sigmaS_(sigmaS),
      sigmaT_(sigmaA + sigmaS),
      grey_(sigmaT_.r == sigmaT_.g && sigmaT_.g == sigmaT_.b),
      phase_(std::move(phase)) {}

Rgb HomogeneousMedium::transmittance(float distance) const {
    return Rgb(static_cast<float>(attenuation(sigmaT_.r, distance)),
               static_cast<float>(attenuation(sigmaT_.g, distance)),
               static_cast<float>(attenuation(sigmaT_.b, distance)));
}

float HomogeneousMedium::survival(float distance) const {
    double sum = 0;
    for (int c = 0; c < 3; ++c)
        sum += attenuation(sigmaT_[c], distance);
    return static_cast<float>(sum / 3);
}

float HomogeneousMedium::distancePdf(float t) const {
    double sum = 0;
    for (int c = 0; c < 3; ++c)
        sum += sigmaT_[c] * attenuation(sigmaT_[c], t);
    return static_cast<float>(sum / 3);
}

float HomogeneousMedium::distanceForSurvival(float v) const {
    const double logV = std::log(static_cast<double>(v));
    if (grey_) return static_cast<float>(-logV / sigmaT_.r);
    // Newton on h(t) = ln S(t) − ln v, convex and decreasing: each step lands left of the
    // root, so t increases monotonically; h' = −pdf/S.
    double t = -logV / sigmaT_.maxComponent();
    for (int i = 0; i < 64; ++i) {
        double s = 0, pdf = 0;
        for (int c = 0; c < 3; ++c) {
            const double e = attenuation(sigmaT_[c], t);
            s += e;
            pdf += sigmaT_[c] * e;
        }
        const double step = (std::log(s / 3) - logV) * s / pdf;
        t += step;
        if (!(step > 1e-9 * t)) break;
    }
    return static_cast<float>(t);
}

FreeFlight HomogeneousMedium::sampleFreeFlight(float budget, float tMax) const {
    FreeFlight f;
    const float passes = survival(tMax);
    if (budget <= passes) {  // passes > 0, as budget > 0
        f.weight = transmittance(tMax) / passes;
        f.survival = passes;
        f.budgetLeft = budget / passes;
        return f;
    }
    const float t = std::fmin(distanceForSurvival(budget), std::nextafter(tMax, 0.0f));
    f.collided = true;
    f.distance = t;
    f.weight = transmittance(t) * sigmaS_ / distancePdf(t);
    return f;
}

}  // namespace rr
