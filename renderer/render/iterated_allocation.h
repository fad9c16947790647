// Iterations whose per-pixel sample counts are computed from the samples so far (adaptive
// sampling: PMC-IP's deterministic mixture, Lai et al. 2007 §4). Before each iteration the
// allocation function fills one count per pixel (row-major), or says the image is done; pixels
// are then rendered over 16×16 tiles in parallel, each pixel's sample indices continuing from
// the samples it already has, so any allocation is deterministic and bit-identical for any
// thread count. An allocation may instead plan a pilot: samples from index kMaxSpp on, which
// no kept sample has, that the observer sees and the film never gets. A time limit stops the
// render between iterations when the next one, predicted to take as long as the last, would
// overrun it. An observer, when given, sees each visit's sample values and their positions in
// the pixel as they are rendered (PMC-IP weights them per iteration); it is called for each
// pixel by the one unit that renders it, so it may write per-pixel state without locks.
#pragma once

#include <functional>

#include "render/render_schedule.h"
#include "render/tile_grid.h"

namespace rr {

class IteratedAllocation final : public RenderSchedule {
  public:
    struct Plan {
        std::vector<uint32_t> counts;  // samples per pixel (width·height entries)
        bool pilot = false;            // samples the film does not keep (indices kMaxSpp on)
    };
    // Fills *plan for iteration `iteration` from `film` (its kept samples so far); false when
    // the image is complete.
    using Allocation = std::function<bool(const Film& film, int iteration, Plan* plan)>;
    // Called after each visit with its values (non-finite ones already replaced by zero) and
    // their positions in the pixel.
    using Observer = std::function<void(const PixelVisit& visit, const std::vector<Rgb>& values,
                                        const std::vector<Vec2>& offsets)>;
    // Called once the schedule ends the render (all iterations done, or the time is up), inside
    // the timed render: where an integrator forms its image.
    using Finish = std::function<void()>;

    IteratedAllocation(const Scene& scene, const SampleIntegrator& integrator, int width,
                       int height, double timeLimit, Allocation allocate, Observer observe = {},
                       Finish finish = {});

    bool supportsTimeLimit() const override { return true; }
    uint64_t plannedSamples() const override { return 0; }
    bool nextRound(const Film& film, const RoundTiming& timing, Round* round) override;
    void unitVisits(size_t unit, std::vector<PixelVisit>* visits) const override;
    std::unique_ptr<PixelRenderer> pixelRenderer(const Sampler& sampler) const override;

  private:
    const Scene& scene_;
    const SampleIntegrator& integrator_;
    TileGrid grid_;
    double timeLimit_;
    Allocation allocate_;
    Observer observe_;
    Finish finish_;
    int iteration_ = 0;
    Plan plan_;                    // this iteration's
    std::vector<uint32_t> first_;  // each pixel's samples before this iteration
};

}  // namespace rr
