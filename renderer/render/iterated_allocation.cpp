#include "render/iterated_allocation.h"

#include <algorithm>
#include <stdexcept>

namespace rr {

IteratedAllocation::IteratedAllocation(const Scene& scene, const SampleIntegrator& integrator,
                                       int width, int height, double timeLimit, Allocation allocate,
                                       Observer observe)
    : scene_(scene),
      integrator_(integrator),
      grid_(width, height),
      timeLimit_(timeLimit),
      allocate_(std::move(allocate)),
      observe_(std::move(observe)),
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

namespace {

// The sample loop, then the observer on the visit's values.
class ObservedSampleLoop final : public PixelRenderer {
  public:
    ObservedSampleLoop(const Scene& scene, const SampleIntegrator& integrator,
                       const Sampler& sampler, int width,
                       const IteratedAllocation::Observer& observe)
        : loop_(scene, integrator, sampler, width), observe_(observe) {}

    void render(const PixelVisit& visit, PixelWork& work) override {
        loop_.render(visit, work);
        finite_.clear();
        uint64_t counted = 0;  // the loop counts them
        for (const Rgb& value : work.values)
            finite_.push_back(finiteOrZero(value, &counted));
        observe_(visit, finite_);
    }

  private:
    SampleLoop loop_;
    const IteratedAllocation::Observer& observe_;
    std::vector<Rgb> finite_;
};

}  // namespace

std::unique_ptr<PixelRenderer> IteratedAllocation::pixelRenderer(const Sampler& sampler) const {
    if (observe_)
        return std::make_unique<ObservedSampleLoop>(scene_, integrator_, sampler, grid_.width(),
                                                    observe_);
    return std::make_unique<SampleLoop>(scene_, integrator_, sampler, grid_.width());
}

}  // namespace rr
