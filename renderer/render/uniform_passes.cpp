#include "render/uniform_passes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rr {

namespace {

constexpr double kTargetPassSeconds = 1.0;

}  // namespace

UniformPasses::UniformPasses(const Scene& scene, const SampleIntegrator& integrator, int width,
                             int height, uint32_t spp, double timeLimit)
    : scene_(scene),
      integrator_(integrator),
      grid_(width, height),
      cap_(spp > 0 ? spp : std::numeric_limits<uint32_t>::max()),
      timeLimit_(timeLimit) {}

uint64_t UniformPasses::plannedSamples() const {
    return timeLimit_ > 0 ? 0 : uint64_t(grid_.width()) * grid_.height() * cap_;
}

bool UniformPasses::nextRound(const Film&, const RoundTiming& timing, Round* round) {
    done_ += count_;
    if (count_ > 0) {  // size the next pass from the last one's time per sample per pixel
        const double secondsPerSpp = std::max(timing.lastRoundSeconds / count_, 1e-9);
        const double target =
            timeLimit_ > 0 ? std::min(kTargetPassSeconds, timeLimit_ / 8) : kTargetPassSeconds;
        passSize_ = static_cast<uint32_t>(
            std::clamp(target / secondsPerSpp, 1.0, 2.0 * std::max<uint32_t>(count_, 1)));
        if (timeLimit_ > 0) {
            const double affordable = std::floor((timeLimit_ - timing.elapsed) / secondsPerSpp);
            if (affordable < 1) return false;
            passSize_ = static_cast<uint32_t>(std::min<double>(passSize_, affordable));
        }
    }
    if (done_ >= cap_) return false;
    count_ = std::min(passSize_, cap_ - done_);
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
