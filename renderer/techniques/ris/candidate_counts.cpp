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

VarianceTerms::Terms VarianceTerms::terms() const {
    Terms t;
    const double n = count_;
    for (int c = 0; c < 3; ++c) {
        t.e1[c] = std::pow(fOverP[c] / n, 2);
        t.e2[c] = fSquaredOverGP[c] / n * (gOverP / n);
        t.e3[c] = fSquaredOverPSquared[c] / n;
    }
    return t;
}

Rgb VarianceTerms::e1() const {
    return fromChannels(terms().e1);
}

Rgb VarianceTerms::e2() const {
    return fromChannels(terms().e2);
}

Rgb VarianceTerms::e3() const {
    return fromChannels(terms().e3);
}

double VarianceTerms::sourceExcess() const {
    const Terms t = terms();
    const double d[3] = {t.e3[0] - t.e2[0], t.e3[1] - t.e2[1], t.e3[2] - t.e2[2]};
    return length(d);
}

double VarianceTerms::targetExcess() const {
    const Terms t = terms();
    const double d[3] = {t.e2[0] - t.e1[0], t.e2[1] - t.e1[1], t.e2[2] - t.e1[2]};
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
