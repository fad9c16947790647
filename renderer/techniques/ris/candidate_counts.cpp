#include "techniques/ris/candidate_counts.h"

#include <algorithm>
#include <cmath>

namespace rr::ris {

namespace {

Rgb fromChannels(const double (&c)[3]) {
    return Rgb(float(c[0]), float(c[1]), float(c[2]));
}

double length(const double (&c)[3]) {
    return std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
}

}  // namespace

void VarianceTerms::add(const Rgb& f, float target, float pdf) {
    ++count_;
    const double channels[3] = {f.r, f.g, f.b};
    for (int c = 0; c < 3; ++c) {
        fOverP[c] += channels[c] / pdf;
        fSquaredOverPSquared[c] += channels[c] * channels[c] / (double(pdf) * pdf);
        if (target > 0) fSquaredOverGP[c] += channels[c] * channels[c] / (double(target) * pdf);
    }
    gOverP += double(target) / pdf;
}

Rgb VarianceTerms::e1() const {
    double e[3];
    for (int c = 0; c < 3; ++c)
        e[c] = std::pow(fOverP[c] / count_, 2);
    return fromChannels(e);
}

Rgb VarianceTerms::e2() const {
    double e[3];
    for (int c = 0; c < 3; ++c)
        e[c] = fSquaredOverGP[c] / count_ * (gOverP / count_);
    return fromChannels(e);
}

Rgb VarianceTerms::e3() const {
    double e[3];
    for (int c = 0; c < 3; ++c)
        e[c] = fSquaredOverPSquared[c] / count_;
    return fromChannels(e);
}

double VarianceTerms::sourceExcess() const {
    double d[3];
    for (int c = 0; c < 3; ++c)
        d[c] = fSquaredOverPSquared[c] / count_ - fSquaredOverGP[c] / count_ * (gOverP / count_);
    return length(d);
}

double VarianceTerms::targetExcess() const {
    double d[3];
    for (int c = 0; c < 3; ++c)
        d[c] = fSquaredOverGP[c] / count_ * (gOverP / count_) - std::pow(fOverP[c] / count_, 2);
    return length(d);
}

double robustCandidates(const CandidateCosts& costs) {
    return costs.tY / costs.tX;
}

double optimalCandidates(const VarianceTerms& terms, const CandidateCosts& costs,
                         double maxCandidates) {
    const double source = terms.sourceExcess(), target = terms.targetExcess();
    if (!(source > 0)) return 1;
    if (!(target > 0)) return maxCandidates;
    return std::sqrt(source / target * costs.tY / costs.tX);
}

CandidateCounts countsWithinBudget(double wantedCandidates, const CandidateCosts& costs,
                                   double budget, double maxCandidates) {
    const double time = budget * (costs.tX + costs.tY);
    const double m = std::clamp(wantedCandidates, 1.0, maxCandidates);
    const double n = std::max(1.0, time / (m * costs.tX + costs.tY));
    return {std::clamp((time / n - costs.tY) / costs.tX, 1.0, maxCandidates), n};
}

}  // namespace rr::ris
