#include "render/uniform_passes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rr {

namespace {

constexpr double kTargetPassSeconds = 1.0;
constexpr double kFixedPassSamples = 1 << 20;

}  // namespace

UniformPasses::UniformPasses(const Scene& scene, const SampleIntegrator& integrator, int width,
                             int height, uint32_t spp, double timeLimit, bool fixedPlan)
    : scene_(scene),
      integrator_(integrator),
      grid_(width, height),
      cap_(spp > 0 ? spp : std::numeric_limits<uint32_t>::max()),
      timeLimit_(timeLimit),
      fixedPlan_(fixedPlan),
      fixedCap_(static_cast<uint32_t>(
          std::max(1.0, std::floor(kFixedPassSamples / (double(width) * height))))) {}

uint64_t UniformPasses::plannedSamples() const {
    return timeLimit_ > 0 ? 0 : uint64_t(grid_.width()) * grid_.height() * cap_;
}

uint32_t UniformPasses::plannedPassSize(const RoundTiming& timing) const {
    if (count_ == 0) return 1;
    if (fixedPlan_) return std::min(2 * passSize_, fixedCap_);
    // The next pass from the last one's time per sample per pixel.
    const double secondsPerSpp = std::max(timing.lastRoundSeconds / count_, 1e-9);
    const double target =
        timeLimit_ > 0 ? std::min(kTargetPassSeconds, timeLimit_ / 8) : kTargetPassSeconds;
    return static_cast<uint32_t>(
        std::clamp(target / secondsPerSpp, 1.0, 2.0 * std::max<uint32_t>(count_, 1)));
}

bool UniformPasses::nextRound(const Film&, const RoundTiming& timing, Round* round) {
    done_ += count_;
    if (done_ >= cap_ || shortened_) return false;
    uint32_t size = plannedPassSize(timing);
    passSize_ = size;
    if (timeLimit_ > 0 && count_ > 0) {
        const double secondsPerSpp = std::max(timing.lastRoundSeconds / count_, 1e-9);
        const double affordable = std::floor((timeLimit_ - timing.elapsed) / secondsPerSpp);
        if (affordable < 1) return false;
        if (affordable < size) {
            size = static_cast<uint32_t>(affordable);
            shortened_ = fixedPlan_;  // the fixed plan's prefix ends here
        }
    }
    count_ = std::min(size, cap_ - done_);
    *round = Round{grid_.tiles(), /*interruptible=*/false};
    return true;
}

void UniformPasses::unitVisits(size_t unit, std::vector<PixelVisit>* visits) const {
    visits->clear();
    grid_.forEachPixel(unit, [&](int x, int y) { visits->push_back({x, y, done_, count_, true}); });
}

std::unique_ptr<PixelRenderer> UniformPasses::pixelRenderer(const Sampler& sampler) const {
    return std::make_unique<SampleLoop>(scene_, integrator_, sampler, grid_.width());
}

}  // namespace rr
