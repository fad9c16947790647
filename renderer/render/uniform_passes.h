// Progressive passes over 16×16 tiles: a pass adds the same range of sample indices to every
// pixel, so every pixel always holds the same number of samples and the image is complete
// after any pass. Passes grow to about a second each; with a time limit, a pass starts only if
// it is predicted to finish in time.
#pragma once

#include "render/render_schedule.h"
#include "render/tile_grid.h"

namespace rr {

class UniformPasses final : public RenderSchedule {
  public:
    // `spp`: samples per pixel, or with a time limit an upper bound (0: none).
    UniformPasses(const Scene& scene, const SampleIntegrator& integrator, int width, int height,
                  uint32_t spp, double timeLimit);

    bool supportsTimeLimit() const override { return true; }
    uint64_t plannedSamples() const override;
    bool nextRound(const Film& film, const RoundTiming& timing, Round* round) override;
    void unitVisits(size_t unit, std::vector<PixelVisit>* visits) const override;
    std::unique_ptr<PixelRenderer> pixelRenderer(const Sampler& sampler) const override;

  private:
    const Scene& scene_;
    const SampleIntegrator& integrator_;
    TileGrid grid_;
    uint32_t cap_;  // the most samples per pixel
    double timeLimit_;
    uint32_t done_ = 0;      // samples per pixel before the current pass
    uint32_t count_ = 0;     // samples per pixel in the current pass
    uint32_t passSize_ = 1;  // the next pass's size before the time check
};

}  // namespace rr
