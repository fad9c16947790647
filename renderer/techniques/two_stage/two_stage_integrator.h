// `two_stage`: direct lighting at the first hit by two-stage sampling (two_stage_estimator.h),
// with the samples per primary ray allocated as Cline et al. 2006 §5 allocates them:
//  - fixed: N samples at every pixel's hit (uniform passes; time limits allowed);
//  - variable: a preprocess inside the timed render takes σ_ave, the mean standard deviation of
//    the samples at `pilot_pixels` pixels spread over the image, N samples each (kept out of
//    the image); then fixed bands of rows are scanned in serpentine order, each pixel getting
//    n = (N/2)(1 + σ_p/σ_ave) samples (eq. 9), where σ_p ← 0.75 σ_p + 0.25 σ_pixel (eq. 8)
//    runs over the pixels scanned before it in its band (0 at the band's start). Unbiased:
//    σ_p does not depend on the pixel's own samples;
//  - variable_rerender: as variable, and a pixel whose σ_pixel > σ_p + σ_ave is rendered again
//    with σ_p = σ_pixel and fresh samples, the second estimate kept (the paper: about 5 % of
//    pixels, "a slight bias").
// σ is the standard deviation of a pixel's per-sample values (luminance); n is rounded to the
// nearest integer in [1, 16 N] (the paper gives no bound). Bands are fixed by the settings, so
// images are the same for any thread count. Writes the samples drawn per pixel (both renders of
// a re-rendered pixel) as the channel two_stage.samples (fig. 10's red image) and records σ_ave,
// the mean drawn count and the re-rendered fraction in the metadata.
#pragma once

#include <atomic>
#include <mutex>
#include <vector>

#include "render/technique_registry.h"
#include "techniques/two_stage/two_stage_estimator.h"

namespace rr::two_stage {

enum class Allocation : uint8_t { Fixed, Variable, VariableRerender };

struct TwoStageIntegratorSettings {
    TwoStageSettings estimator;
    Allocation allocation = Allocation::Fixed;
    uint32_t pilotPixels = 1024;
    int bandRows = 16;
};

class TwoStageIntegrator final : public SampleIntegrator {
  public:
    // The most samples eq. (9) gives a pixel, in multiples of N.
    static constexpr uint32_t kMaxSampleFactor = 16;

    explicit TwoStageIntegrator(const TwoStageIntegratorSettings& settings)
        : settings_(settings), estimator_(settings.estimator) {}

    std::string name() const override { return "two_stage"; }
    LightTransport transport() const override { return LightTransport::Direct; }
    nlohmann::json parameters() const override;
    uint32_t decisionRepeats() const override;
    void prepare(const Scene& scene) override { estimator_.prepare(scene, "/integrator"); }
    // One primary ray with N samples at its hit (fixed allocation).
    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                 RayCounters& rays) const override {
        return estimate(scene, x, y, sample, settings_.estimator.samples, rays, nullptr);
    }
    // One primary ray with `samples` samples at its hit; their values' moments into *moments.
    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample, uint32_t samples,
                 RayCounters& rays, SampleMoments* moments) const;
    std::vector<AuxiliaryChannel> auxiliaryChannels() const override;

    std::unique_ptr<RenderSchedule> schedule(const ScheduleInputs& inputs);

    // §5, for the schedule's hooks:
    const TwoStageIntegratorSettings& settings() const { return settings_; }
    // Eq. (9): the samples of the next pixel.
    uint32_t allocate(double sigmaP) const;
    double sigmaAverage() const { return sigmaAverage_; }
    void addPilot(double sigmaSum, uint64_t pixels) const;
    // After the preprocess: σ_ave from the pilot's pixels.
    void resolveSigmaAverage();
    // A pixel sample's drawn samples (both renders of a re-rendered one).
    void recordPixel(int x, int y, uint32_t samples, bool rerendered) const;

  private:
    TwoStageIntegratorSettings settings_;
    TwoStageEstimator estimator_;
    int width_ = 0;
    double sigmaAverage_ = 0;
    mutable std::mutex mutex_;
    mutable double pilotSigmaSum_ = 0;
    mutable uint64_t pilotPixelsDone_ = 0;
    mutable std::vector<float> pixelSamples_;  // variable: the samples each pixel got
    mutable std::atomic<uint64_t> rerendered_{0}, allocated_{0}, pixelsDone_{0};
};

}  // namespace rr::two_stage
