// `pmc_ip`: population Monte Carlo on the image plane (Lai et al. 2007 §4). Any integrator
// whose pixel samples are independent (path, path_mis, direct, ris, …) renders the samples; this
// one decides how many each pixel gets:
//  - iteration 0: a uniform image of `initial_spp` samples per pixel;
//  - iteration t ≥ 1: N = |P| × `iteration_spp` samples spread by the mixture kernel, α from
//    the image so far (§4.2) and counts by deterministic mixture sampling (§4.3);
//    mixture_allocation.h has both steps;
//  - until the render's spp or its time limit is reached; the last iteration takes what is
//    left of the spp when `iteration_spp` does not divide it.
// Each pixel's sample indices continue across iterations (render/iterated_allocation.h), so a
// structured sampler's sets carry on across them. The adaptation runs between iterations inside
// the timed render, so times and P-Eff charge it.
//
// The image. A pixel can get no sample in an iteration, so the paper's "average of the
// sub-images" needs a per-iteration estimate defined for every pixel. Iteration t's is
// c + Σ (L − c) / (N α_ij): the pixel's samples against their expected count (E[n_ij] = N α_ij),
// with the control variate c, the pixel's mean before the iteration (0 for the initial image;
// README.md, "The image"). α and c depend on earlier samples only, so each iteration's estimate
// is unbiased for the independent sampler; the image is the unweighted mean of the completed
// iterations' estimates (`image`: "iterations", the default), and its variance channels the
// variance of that mean from the spread of the iterations' estimates. `image`: "pooled" takes
// the mean of all the pixel's samples instead, which is biased (a pixel whose first samples
// missed a highlight looks flat and gets few more; README.md).
//
// Channels besides radiance: pmc.alpha, |P|·α of the last iteration (1 = a uniform share; the
// α image of fig. 4), and pmc.variance, the per-sample luminance variance it came from.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "render/technique_registry.h"

namespace rr::pmc {

enum class ImageEstimate : uint8_t { Iterations, Pooled };

struct PmcIpSettings {
    uint32_t initialSpp = 2;    // the uniform initial image; at least 2 for a variance
    uint32_t iterationSpp = 4;  // N = |P| × this per adaptive iteration
    double epsilon = 0.01;      // the defensive uniform share of α (§4.2)
    ImageEstimate image = ImageEstimate::Iterations;
};

class PmcIpIntegrator final : public Integrator {
  public:
    PmcIpIntegrator(std::unique_ptr<SampleIntegrator> pixelIntegrator,
                    const PmcIpSettings& settings);

    std::string name() const override { return "pmc_ip"; }
    nlohmann::json parameters() const override;
    uint32_t decisionRepeats() const override { return pixelIntegrator_->decisionRepeats(); }
    void prepare(const Scene& scene) override { pixelIntegrator_->prepare(scene); }
    std::vector<AuxiliaryChannel> auxiliaryChannels() const override;
    PixelEstimates pixelEstimates() const override;

    std::unique_ptr<RenderSchedule> schedule(const ScheduleInputs& inputs);

  private:
    // What the adaptation and the image need of a pixel, gathered from its samples as they are
    // rendered (by the one unit that renders the pixel in an iteration).
    struct PixelState {
        double luminanceSum = 0, luminanceSquares = 0;
        uint32_t samples = 0;
        double rgbSum[3] = {0, 0, 0};
        double control[3] = {0, 0, 0};       // c of the current iteration
        double iterationSum[3] = {0, 0, 0};  // Σ (L − c) / (N α) of the current iteration
        double estimateSum[3] = {0, 0, 0};   // Σ over completed iterations of their estimates
        double estimateSquares[3] = {0, 0, 0};
    };

    bool allocate(int iteration, std::vector<uint32_t>* counts);
    void adapt(std::vector<uint32_t>* counts);
    void observe(const PixelVisit& visit, const std::vector<Rgb>& values);
    // Adds the current iteration to the completed ones, if its round ran (a render cancelled
    // between planning and running a round never runs it).
    void completeIteration();
    bool currentIterationRan() const { return planned_ && ran_.load(std::memory_order_relaxed); }
    int completedIterations() const { return iterationsDone_ + (currentIterationRan() ? 1 : 0); }

    std::unique_ptr<SampleIntegrator> pixelIntegrator_;
    PmcIpSettings settings_;
    int width_ = 0;
    uint32_t seed_ = 0;
    int maxIterations_ = 0;  // adaptive iterations the spp allows
    uint32_t lastIterationSpp_ = 0;
    int iterationsDone_ = 0;  // completed and added up, the initial one included
    bool planned_ = false;    // an iteration has been planned and not yet added up
    std::atomic<bool> ran_{false};
    double adaptSeconds_ = 0;
    std::vector<PixelState> pixels_;
    std::vector<double> alpha_;
    std::vector<double> sampleWeight_;  // this iteration's 1 / (N α) per pixel
    std::vector<double> variance_;      // the per-sample luminance variance α last came from
};

}  // namespace rr::pmc
