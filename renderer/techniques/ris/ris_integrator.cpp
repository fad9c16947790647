#include "techniques/ris/ris_integrator.h"

#include "integrators/direct_lighting.h"
#include "techniques/ris/ris_schedule.h"

namespace rr::ris {

namespace {

// The largest M and N a render may use: the given ones, or within the budget (N ≤ budget
// because M ≥ 1; M ≤ maxCandidates).
CandidateCounts maxCounts(const RisSettings& s) {
    if (s.choice == CountChoice::Fixed) return s.counts;
    return {s.maxCandidates, s.budget};
}

}  // namespace

RisIntegrator::RisIntegrator(const RisSettings& settings)
    : settings_(settings),
      estimator_(settings.source, settings.counts, maxCounts(settings)),
      counts_(settings.counts) {}

nlohmann::json RisIntegrator::parameters() const {
    // The counts used (fixed or chosen) and the costs they were chosen by.
    nlohmann::json p = readParameters();
    p["candidates"] = counts_.m;
    p["samples"] = counts_.n;
    if (settings_.choice == CountChoice::Fixed) return p;
    p["t_x_ns"] = costs_.tX * 1e9;
    p["t_y_ns"] = costs_.tY * 1e9;
    p["costs"] = settings_.costs ? "given" : "measured";
    return p;
}

nlohmann::json RisIntegrator::pinnedSettings() const {
    if (!needsCostPilot()) return nlohmann::json::object();
    // A candidate a quarter of a shadow ray: robust M = 4, so that resampling is exercised.
    return {{"costs", {{"t_x_ns", 50.0}, {"t_y_ns", 200.0}}}};
}

template <class Use>
Rgb RisIntegrator::atFirstHit(const Scene& scene, int x, int y, const PixelSample& sample,
                              RayCounters& rays, const Use& use) const {
    StandardSampling standard(scene, sample);
    return estimateAtFirstHit(scene, standard, x, y, rays, use);
}

Rgb RisIntegrator::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                            RayCounters& rays) const {
    const CandidateCounts& counts =
        pixelCounts_.empty() ? counts_ : pixelCounts_[size_t(y) * width_ + x];
    return atFirstHit(scene, x, y, sample, rays,
                      [&](ShadingPoint& point) { estimator_.estimate(point, counts); });
}

bool RisIntegrator::needsCostPilot() const {
    return settings_.choice != CountChoice::Fixed && !settings_.costs;
}

void RisIntegrator::measureCosts(const Scene& scene, int x, int y, const PixelSample& sample,
                                 RayCounters& rays, bool timed, CostTally* tally) const {
    atFirstHit(scene, x, y, sample, rays,
               [&](ShadingPoint& point) { estimator_.measureCosts(point, timed, tally); });
}

void RisIntegrator::measureTerms(const Scene& scene, int x, int y, const PixelSample& sample,
                                 RayCounters& rays) {
    VarianceTerms& terms = pixelTerms_[size_t(y) * width_ + x];
    atFirstHit(scene, x, y, sample, rays, [&](ShadingPoint& point) {
        estimator_.addVarianceTerms(point, settings_.pilotSamples, &terms);
    });
}

void RisIntegrator::resolveCounts(const CandidateCosts& measured) {
    if (settings_.choice == CountChoice::Fixed) return;
    costs_ = settings_.costs ? *settings_.costs : measured;
    // No shading point in the pilot: §4.3's default T_X = T_Y (M = 1, plain light sampling).
    if (!(costs_.tX > 0 && costs_.tY > 0)) costs_ = {1, 1};
    const double budget = settings_.budget, maxM = settings_.maxCandidates;
    const CandidateCounts robust =
        countsWithinBudget(robustCandidates(costs_), costs_, budget, maxM);
    counts_ = robust;
    if (settings_.choice == CountChoice::Robust) return;
    pixelCounts_.assign(pixelTerms_.size(), robust);
    CandidateCounts sum{0, 0};
    size_t measuredPixels = 0;
    for (size_t i = 0; i < pixelTerms_.size(); ++i) {
        if (pixelTerms_[i].count() == 0) continue;  // no shading point: robust M and N
        pixelCounts_[i] = countsWithinBudget(optimalCandidates(pixelTerms_[i], costs_, maxM),
                                             costs_, budget, maxM);
        sum.m += pixelCounts_[i].m;
        sum.n += pixelCounts_[i].n;
        ++measuredPixels;
    }
    if (measuredPixels) counts_ = {sum.m / double(measuredPixels), sum.n / double(measuredPixels)};
}

std::vector<AuxiliaryChannel> RisIntegrator::auxiliaryChannels() const {
    if (pixelCounts_.empty()) return {};
    AuxiliaryChannel ratio{"ris.mOverN",
                           "optimal M/N per pixel (eq. 3 within the budget; 0: no shading point)",
                           std::vector<float>(pixelCounts_.size(), 0.0f)};
    for (size_t i = 0; i < pixelCounts_.size(); ++i)
        if (pixelTerms_[i].count() > 0)
            ratio.values[i] = static_cast<float>(pixelCounts_[i].m / pixelCounts_[i].n);
    return {ratio};
}

std::unique_ptr<RenderSchedule> RisIntegrator::schedule(const ScheduleInputs& in) {
    width_ = in.width;
    if (needsTermsPilot()) pixelTerms_.assign(size_t(in.width) * in.height, VarianceTerms{});
    return std::make_unique<RisSchedule>(*this, in);
}

}  // namespace rr::ris
