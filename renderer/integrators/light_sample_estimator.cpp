#include "integrators/light_sample_estimator.h"

namespace rr {

nlohmann::json LightSampleEstimator::parameters() const {
    return {{"type", name()}, {"light_samples", lightSamples_}};
}

void LightSampleEstimator::estimate(ShadingPoint& point) const {
    const float n = static_cast<float>(lightSamples_);
    for (uint32_t r = 0; r < lightSamples_; ++r) {
        LightSample ls;
        float pdf;
        const Light* light;
        if (!point.sampleLight(r, lightSamples_, &ls, &pdf, &light)) continue;
        const Rgb f = point.scattering(ls.direction);
        if (f.isBlack()) continue;
        float survival;
        const Rgb tr = point.visibility(ls, light->isInfinite(), &survival);
        if (tr.isBlack()) continue;
        // A delta light cannot be found by scattering: its samples count in full.
        const float weight = mis_ && !ls.isDelta
                                 ? powerHeuristic(n, pdf, point.scatteringSamples(),
                                                  point.scatteringPdf(ls.direction) * survival)
                                 : 1.0f;
        point.add(point.contribution(f, ls.radiance, tr, weight, pdf * n));
    }
}

}  // namespace rr
