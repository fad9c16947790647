// `ris`: direct lighting at the first hit by resampled importance sampling (ris_estimator.h),
// with M and N chosen as Talbot et al. 2005 choose them:
//  - fixed: M and N as given;
//  - robust (§4.3, eq. 4): M = T_Y/T_X, N from the time budget;
//  - optimal (§4.2, eq. 3): M from eq. (2)'s terms e1, e2, e3, estimated per pixel by a pilot
//    that finishes `pilot_samples` light samples at the pixel's first hit, and N from the budget.
// The budget is the time of `budget` plain light samples per shading point (the paper's
// baseline, M = 1 and N = 20 in fig. 4): T = budget · (T_X + T_Y).
// T_X (draw a candidate, evaluate its weight) and T_Y (finish a chosen sample: its shadow ray)
// are measured by a pilot over `pilot_rays` primary rays (§5.1: "a few thousand") inside the
// timed render, so equal-time comparisons pay for it; or given as "costs", which makes robust
// and optimal renders reproducible bit for bit (measured costs vary from run to run, and so do
// M and N). The parameters the output records include the costs, M and N used; optimal also
// writes the per-pixel M/N (channel ris.mOverN, fig. 3's lower image).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "render/technique_registry.h"
#include "techniques/ris/ris_estimator.h"

namespace rr::ris {

enum class CountChoice : uint8_t { Fixed, Robust, Optimal };

struct RisSettings {
    CandidateSource source = CandidateSource::Light;
    CountChoice choice = CountChoice::Fixed;
    CandidateCounts counts;  // fixed
    double budget = 1;       // robust, optimal: plain light samples' time per shading point
    double maxCandidates = 1024;
    uint32_t pilotRays = 4096;
    uint32_t pilotSamples = 16;           // optimal: light samples per pixel for e1..e3
    std::optional<CandidateCosts> costs;  // given instead of measured
};

class RisIntegrator final : public SampleIntegrator {
  public:
    explicit RisIntegrator(const RisSettings& settings);

    std::string name() const override { return "ris"; }
    LightTransport transport() const override { return LightTransport::Direct; }
    bool samplesLights() const override { return estimator_.samplesLights(); }
    nlohmann::json parameters() const override;
    uint32_t decisionRepeats() const override { return estimator_.decisionRepeats(); }
    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                 RayCounters& rays) const override;
    std::vector<AuxiliaryChannel> auxiliaryChannels() const override;
    // Robust and optimal M and N follow the measured costs: pinned, given costs.
    nlohmann::json pinnedSettings() const override;
    void prepare(const Scene& scene) override { estimator_.prepare(scene, "/integrator"); }

    std::unique_ptr<RenderSchedule> schedule(const ScheduleInputs& inputs);

    // The pilot, pixel by pixel (ris_schedule.h).
    void measureCosts(const Scene& scene, int x, int y, const PixelSample& sample,
                      RayCounters& rays, bool timed, CostTally* tally) const;
    void measureTerms(const Scene& scene, int x, int y, const PixelSample& sample,
                      RayCounters& rays);
    // Between the pilot and the render: M and N from the costs (and each pixel's terms).
    void resolveCounts(const CandidateCosts& measured);

    const RisSettings& settings() const { return settings_; }
    bool needsCostPilot() const;
    bool needsTermsPilot() const { return settings_.choice == CountChoice::Optimal; }

  private:
    // Calls `use(point)` with the shading point of the pixel sample's first hit.
    template <class Use>
    Rgb atFirstHit(const Scene& scene, int x, int y, const PixelSample& sample, RayCounters& rays,
                   const Use& use) const;

    RisSettings settings_;
    RisEstimator estimator_;
    int width_ = 0;
    CandidateCosts costs_;
    CandidateCounts counts_;                    // fixed and robust; optimal: the image's mean
    std::vector<VarianceTerms> pixelTerms_;     // optimal
    std::vector<CandidateCounts> pixelCounts_;  // optimal
};

}  // namespace rr::ris
