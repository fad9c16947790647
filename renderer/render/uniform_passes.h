// Progressive passes over 16×16 tiles: a pass adds the same range of sample indices to every
// pixel, so every pixel always holds the same number of samples and the image is complete
// after any pass. With a time limit, a pass starts only if it is predicted to finish in time.
// Pass sizes:
//  - timed (box film): passes grow to about a second each;
//  - fixed (a splatting film, whose sums depend on the cut into passes): 1, 2, 4, … samples
//    per pixel, at most ⌊2^20 / pixels⌋ (at least 1), whatever the timing. A time limit can
//    only shorten the last pass, so an image reached in time equals the fixed-spp render of
//    the spp it reached.
#pragma once

#include "render/render_schedule.h"
#include "render/tile_grid.h"

namespace rr {

class UniformPasses final : public RenderSchedule {
  public:
    // `spp`: samples per pixel, or with a time limit an upper bound (0: none). `fixedPlan`: pass
    // sizes by the fixed plan above instead of by timing.
    UniformPasses(const Scene& scene, const SampleIntegrator& integrator, int width, int height,
                  uint32_t spp, double timeLimit, bool fixedPlan = false);

    bool supportsTimeLimit() const override { return true; }
    uint64_t plannedSamples() const override;
    bool nextRound(const Film& film, const RoundTiming& timing, Round* round) override;
    void unitVisits(size_t unit, std::vector<PixelVisit>* visits) const override;
    std::unique_ptr<PixelRenderer> pixelRenderer(const Sampler& sampler) const override;

  private:
    // The next pass's size before the time check.
    uint32_t plannedPassSize(const RoundTiming& timing) const;

    const Scene& scene_;
    const SampleIntegrator& integrator_;
    TileGrid grid_;
    uint32_t cap_;  // the most samples per pixel
    double timeLimit_;
    bool fixedPlan_;
    uint32_t fixedCap_;       // the fixed plan's largest pass
    uint32_t done_ = 0;       // samples per pixel before the current pass
    uint32_t count_ = 0;      // samples per pixel in the current pass
    uint32_t passSize_ = 1;   // the size the current pass was planned with
    bool shortened_ = false;  // the current pass was cut short by the time limit: the last
};

}  // namespace rr
