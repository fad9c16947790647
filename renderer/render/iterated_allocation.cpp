#include "render/iterated_allocation.h"

#include <algorithm>
#include <stdexcept>

#include "render/renderer.h"

namespace rr {

IteratedAllocation::IteratedAllocation(const Scene& scene, const SampleIntegrator& integrator,
                                       int width, int height, double timeLimit, Allocation allocate,
                                       Observer observe, Finish finish)
    : scene_(scene),
      integrator_(integrator),
      grid_(width, height),
      timeLimit_(timeLimit),
      allocate_(std::move(allocate)),
      observe_(std::move(observe)),
      finish_(std::move(finish)),
      first_(size_t(width) * height) {}

bool IteratedAllocation::nextRound(const Film& film, const RoundTiming& timing, Round* round) {
    auto end = [&] {
        if (finish_) finish_();
        return false;
    };
    // The next iteration is predicted to take as long as the last one (a pilot predicts
    // nothing).
    if (timeLimit_ > 0 && iteration_ > 0 && !plan_.pilot &&
        timing.elapsed + timing.lastRoundSeconds > timeLimit_)
        return end();
    plan_.pilot = false;
    if (!allocate_(film, iteration_, &plan_)) return end();
    if (plan_.counts.size() != first_.size())
        throw std::logic_error("an allocation must give one count per pixel");
    for (int y = 0; y < grid_.height(); ++y)
        for (int x = 0; x < grid_.width(); ++x)
            first_[size_t(y) * grid_.width() + x] = plan_.pilot ? kMaxSpp : film.sampleCount(x, y);
    ++iteration_;
    *round = Round{grid_.tiles(), /*interruptible=*/false};
    return true;
}

void IteratedAllocation::unitVisits(size_t unit, std::vector<PixelVisit>* visits) const {
    visits->clear();
    grid_.forEachPixel(unit, [&](int x, int y) {
        const size_t pixel = size_t(y) * grid_.width() + x;
        if (plan_.counts[pixel] > 0)
            visits->push_back({x, y, first_[pixel], plan_.counts[pixel], !plan_.pilot});
    });
}

namespace {

// The sample loop, with the samples' positions, then the observer on the visit's values.
class ObservedSampleLoop final : public PixelRenderer {
  public:
    ObservedSampleLoop(const Scene& scene, const SampleIntegrator& integrator,
                       const Sampler& sampler, int width,
                       const IteratedAllocation::Observer& observe)
        : loop_(scene, integrator, sampler, width), observe_(observe) {}

    void render(const PixelVisit& visit, PixelWork& work) override {
        const bool filmWantsOffsets = work.recordOffsets;
        work.recordOffsets = true;
        loop_.render(visit, work);
        work.recordOffsets = filmWantsOffsets;
        finite_.clear();
        uint64_t counted = 0;  // the loop counts them
        for (const Rgb& value : work.values)
            finite_.push_back(finiteOrZero(value, &counted));
        observe_(visit, finite_, work.offsets);
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
