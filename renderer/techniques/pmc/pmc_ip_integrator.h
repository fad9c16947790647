// `pmc_ip`: population Monte Carlo on the image plane (Lai et al. 2007 §4). Any integrator
// whose pixel samples are independent (path, path_mis, direct, ris, …) renders the samples; this
// one decides how many each pixel gets:
//  - iteration 0: a uniform image of `initial_spp` samples per pixel;
//  - iteration t ≥ 1: N = |P| × `iteration_spp` samples spread by the mixture kernel, α from
//    the variance image so far (§4.2) and counts by deterministic mixture sampling (§4.3);
//    mixture_allocation.h has both steps;
//  - until the render's spp or its time limit is reached; the last iteration takes what is
//    left of the spp when `iteration_spp` does not divide it.
// Each pixel's sample indices continue across iterations (render/iterated_allocation.h), so a
// structured sampler's sets carry on across them. The adaptation, and forming the image, run
// inside the timed render, so times and P-Eff charge them.
//
// The film's reconstruction filter is eq. (2)'s W_ij: the variance image is taken over the
// samples within each pixel's filter support, and the images pass through the filter
// (sample_record.h). With the box filter both are the pixel's own samples. The images:
//  - "iterations" (default): unbiased. A pixel can get no sample in an iteration, so the
//    paper's "average of the sub-images" needs a per-iteration estimate defined for every
//    pixel: iteration t's is c + Σ w (L − c) / q / W, the samples weighted by the density q
//    they were drawn with (E[n] = N α per pixel) and the control value c, the pooled image
//    before the iteration (0 for the initial image; README.md, "The image"). α and c depend on
//    earlier samples only, so each iteration's estimate is unbiased for the independent
//    sampler; the image is the unweighted mean of the completed iterations' estimates, and its
//    variance channels the variance of that mean from their spread. An equal-weight mean of
//    an initial image of n₀ spp and further iterations has at least 1/T² of the initial
//    image's variance: against uniform sampling at n spp it cannot gain more than T² n₀ / n
//    (×1.8 for 2 + 4 + 4 against 10; analysis.md).
//  - "pooled": every sample at once, each weighted by the filter and 1 / its pixel's count
//    (Σ w L / n ÷ Σ w / n; for the box, the mean of the pixel's samples), what adaptive
//    samplers usually show and what the paper's gains need. Biased: a pixel whose first samples
//    happened to agree gets few more and keeps their error (README.md).
//
// `known_variance_spp` K > 0 replaces the adaptation by the best static allocation with σ²
// known (a bound for the tables, not the paper's method): a pilot of K spp, kept out of the
// image and of the spp count, gives the variance image; then all the render's samples are
// spread at once, n = max(1, λ σ/√tvi) (mixture_allocation.h: staticAllocation).
//
// Channels besides radiance: pmc.alpha, |P|·α of the last iteration (1 = a uniform share; the
// α image of fig. 4), and pmc.variance, the per-sample luminance variance it came from.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "render/iterated_allocation.h"
#include "render/technique_registry.h"
#include "techniques/pmc/sample_record.h"

namespace rr::pmc {

enum class ImageEstimate : uint8_t { Iterations, Pooled };

struct PmcIpSettings {
    uint32_t initialSpp = 2;    // the uniform initial image; at least 2 for a variance
    uint32_t iterationSpp = 4;  // N = |P| × this per adaptive iteration
    double epsilon = 0.01;      // the defensive uniform share of α (§4.2)
    ImageEstimate image = ImageEstimate::Iterations;
    uint32_t knownVarianceSpp = 0;  // > 0: the static allocation from a pilot of this many spp
};

class PmcIpIntegrator final : public Integrator {
  public:
    PmcIpIntegrator(std::unique_ptr<SampleIntegrator> pixelIntegrator,
                    const PmcIpSettings& settings);

    std::string name() const override { return "pmc_ip"; }
    // PMC-IP reallocates the samples of its pixel integrator, whose image it estimates.
    LightTransport transport() const override { return pixelIntegrator_->transport(); }
    bool samplesLights() const override { return pixelIntegrator_->samplesLights(); }
    nlohmann::json parameters() const override;
    uint32_t decisionRepeats() const override { return pixelIntegrator_->decisionRepeats(); }
    void prepare(const Scene& scene) override { pixelIntegrator_->prepare(scene); }
    std::vector<AuxiliaryChannel> auxiliaryChannels() const override;
    bool formsOwnImage() const override { return true; }
    PixelEstimates pixelEstimates() const override;

    std::unique_ptr<RenderSchedule> schedule(const ScheduleInputs& inputs);

  private:
    bool allocate(int iteration, IteratedAllocation::Plan* plan);
    bool allocateKnownVariance(int iteration, IteratedAllocation::Plan* plan);
    // §4.2 then §4.3 for the next iteration, timed.
    void adapt(IteratedAllocation::Plan* plan);
    void observe(const PixelVisit& visit, const std::vector<Rgb>& values,
                 const std::vector<Vec2>& offsets);
    // Adds the current iteration to the completed ones, if its round ran (a render cancelled
    // between planning and running a round never runs it).
    void completeIteration();
    // Completes the last iteration and forms the image (inside the timed render when the
    // render ends by the schedule's choice).
    void finish();
    bool currentIterationRan() const { return planned_ && ran_.load(std::memory_order_relaxed); }
    // Fills plan->counts by deterministic mixture sampling of `total` samples over α.
    void drawCounts(uint64_t total, IteratedAllocation::Plan* plan) const;
    PixelEstimates iterationsImage() const;

    std::unique_ptr<SampleIntegrator> pixelIntegrator_;
    PmcIpSettings settings_;
    int width_ = 0;
    uint32_t seed_ = 0;
    uint32_t spp_ = 0;
    int maxIterations_ = 0;  // adaptive iterations the spp allows
    uint32_t lastIterationSpp_ = 0;
    int iterationsDone_ = 0;  // completed and added up, the initial one included
    bool planned_ = false;    // an iteration has been planned and not yet added up
    bool pilot_ = false;      // the planned iteration is the known-variance pilot
    std::atomic<bool> ran_{false};
    double adaptSeconds_ = 0;
    std::optional<SampleRecord> record_;
    std::vector<double> alpha_;
    std::vector<double> variance_;  // the per-sample luminance variance α last came from
    std::vector<Rgb> control_;      // c of the current iteration
    // Per pixel, over the completed iterations' estimates: their sum and sum of squares.
    struct EstimateMoments {
        double sum[3] = {0, 0, 0}, squares[3] = {0, 0, 0};
    };
    std::vector<EstimateMoments> estimates_;
    PixelEstimates image_;  // formed by finish()
};

}  // namespace rr::pmc
