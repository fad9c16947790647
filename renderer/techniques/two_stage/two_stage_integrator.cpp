#include "techniques/two_stage/two_stage_integrator.h"

#include <algorithm>
#include <cmath>

#include "integrators/direct_lighting.h"
#include "techniques/two_stage/two_stage_schedule.h"

namespace rr::two_stage {

namespace {

const char* allocationName(Allocation a) {
    switch (a) {
        case Allocation::Fixed:
            return "fixed";
        case Allocation::Variable:
            return "variable";
        case Allocation::VariableRerender:
            return "variable_rerender";
    }
    return "?";
}

}  // namespace

nlohmann::json TwoStageIntegrator::parameters() const {
    nlohmann::json p = readParameters();
    p.update(estimator_.parameters());
    p["type"] = name();
    p["allocation"] = allocationName(settings_.allocation);
    if (settings_.allocation == Allocation::Fixed) return p;
    p["sigma_ave"] = sigmaAverage_;
    const uint64_t pixels = pixelsDone_.load();
    if (pixels > 0) {
        p["mean_samples"] = double(allocated_.load()) / double(pixels);
        p["rerendered_fraction"] = double(rerendered_.load()) / double(pixels);
    }
    return p;
}

uint32_t TwoStageIntegrator::decisionRepeats() const {
    const uint32_t n = settings_.estimator.samples;
    return settings_.allocation == Allocation::Fixed ? estimator_.decisionRepeats()
                                                     : kMaxSampleFactor * n;
}

Rgb TwoStageIntegrator::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                                 uint32_t samples, RayCounters& rays,
                                 SampleMoments* moments) const {
    StandardSampling standard(scene, sample);
    return estimateAtFirstHit(scene, standard, x, y, rays, [&](ShadingPoint& point) {
        estimator_.estimate(point, samples, moments);
    });
}

uint32_t TwoStageIntegrator::allocate(double sigmaP) const {
    const double n = settings_.estimator.samples;
    // Eq. (9); before σ_ave is known (or where it is 0: a black image) the fixed count.
    const double wanted = sigmaAverage_ > 0 ? 0.5 * n * (1 + sigmaP / sigmaAverage_) : n;
    return static_cast<uint32_t>(std::clamp(std::round(wanted), 1.0, kMaxSampleFactor * n));
}

void TwoStageIntegrator::addPilot(double sigmaSum, uint64_t pixels) const {
    std::lock_guard lock(mutex_);
    pilotSigmaSum_ += sigmaSum;
    pilotPixelsDone_ += pixels;
}

void TwoStageIntegrator::resolveSigmaAverage() {
    sigmaAverage_ = pilotPixelsDone_ > 0 ? pilotSigmaSum_ / double(pilotPixelsDone_) : 0;
}

void TwoStageIntegrator::recordPixel(int x, int y, uint32_t samples, bool rerendered) const {
    pixelSamples_[size_t(y) * width_ + x] += float(samples);
    allocated_ += samples;
    ++pixelsDone_;
    if (rerendered) ++rerendered_;
}

std::vector<AuxiliaryChannel> TwoStageIntegrator::auxiliaryChannels() const {
    if (pixelSamples_.empty()) return {};
    return {{"two_stage.samples",
             "two-stage samples drawn per pixel (eq. 9; both renders of a re-rendered pixel)",
             pixelSamples_}};
}

std::unique_ptr<RenderSchedule> TwoStageIntegrator::schedule(const ScheduleInputs& in) {
    width_ = in.width;
    pixelSamples_.assign(size_t(in.width) * in.height, 0.0f);
    return std::make_unique<TwoStageSchedule>(*this, in);
}

}  // namespace rr::two_stage
