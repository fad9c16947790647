#include "render/iterated_allocation.h"

#include <algorithm>
#include <stdexcept>

namespace rr {

IteratedAllocation::IteratedAllocation(const Scene& scene, const SampleIntegrator& integrator,
                                       int width, int height, double timeLimit, Allocation allocate)
    : scene_(scene),
      integrator_(integrator),
      grid_(width, height),
      timeLimit_(timeLimit),
      allocate_(std::move(allocate)),
      counts_(size_t(width) * height),
      first_(size_t(width) * height) {}

bool IteratedAllocation::nextRound(const Film& film, const RoundTiming& timing, Round* round) {
    if (timeLimit_ > 0 && iteration_ > 0 && timing.elapsed + timing.lastRoundSeconds > timeLimit_)
        return false;
    if (!allocate_(film, iteration_, &counts_)) return false;
    if (counts_.size() != first_.size())
        throw std::logic_error("an allocation must give one count per pixel");
    for (int y = 0; y < grid_.height(); ++y)
        for (int x = 0; x < grid_.width(); ++x)
            first_[size_t(y) * grid_.width() + x] = film.sampleCount(x, y);
    ++iteration_;
    *round = Round{grid_.tiles(), /*interruptible=*/false};
    return true;
}

void IteratedAllocation::unitVisits(size_t unit, std::vector<PixelVisit>* visits) const {
    visits->clear();
    grid_.forEachPixel(unit, [&](int x, int y) {
        const size_t pixel = size_t(y) * grid_.width() + x;
        if (counts_[pixel] > 0) visits->push_back({x, y, first_[pixel], counts_[pixel], true});
    });
}

std::unique_ptr<PixelRenderer> IteratedAllocation::pixelRenderer(const Sampler& sampler) const {
    return std::make_unique<SampleLoop>(scene_, integrator_, sampler, grid_.width());
}

}  // namespace rr
