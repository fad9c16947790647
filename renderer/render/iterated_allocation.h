// Iterations whose per-pixel sample counts are computed from the film so far (adaptive
// sampling: PMC-IP's deterministic mixture, Lai et al. 2007 §4). Before each iteration the
// allocation function fills one count per pixel (row-major) from the film, or says the image is
// done; pixels are then rendered over 16×16 tiles in parallel, each pixel's sample indices
// continuing from the samples it already has, so any allocation is deterministic and
// bit-identical for any thread count. A time limit stops the render between iterations when
// the next one, predicted to take as long as the last, would overrun it. An observer, when
// given, sees each visit's sample values as the film gets them (PMC-IP weights them per
// iteration); it is called for each pixel by the one unit that renders it, so it may write
// per-pixel state without locks.
#pragma once

#include <functional>

#include "render/render_schedule.h"
#include "render/tile_grid.h"

namespace rr {

class IteratedAllocation final : public RenderSchedule {
  public:
    // Fills *counts (width·height entries) for iteration `iteration` from `film`; false when
    // the image is complete.
    using Allocation =
        std::function<bool(const Film& film, int iteration, std::vector<uint32_t>* counts)>;
    // Called after each visit with its values (non-finite ones already replaced by zero).
    using Observer = std::function<void(const PixelVisit& visit, const std::vector<Rgb>& values)>;

    IteratedAllocation(const Scene& scene, const SampleIntegrator& integrator, int width,
                       int height, double timeLimit, Allocation allocate, Observer observe = {});

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
    int iteration_ = 0;
    std::vector<uint32_t> counts_;  // this iteration's samples per pixel
    std::vector<uint32_t> first_;   // each pixel's samples before this iteration
};

}  // namespace rr
