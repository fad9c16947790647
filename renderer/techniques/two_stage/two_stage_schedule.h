// The `two_stage` integrator's schedule for variable allocation (§5), inside the timed render:
//  1. the preprocess: `pilot_pixels` pixels spread evenly over the image, each rendered with N
//     samples at sample index kMaxSpp (which no kept sample has) and kept out of the image; the
//     mean of their σ is σ_ave;
//  2. fixed bands of `band_rows` rows, each scanned in serpentine order by one unit whose hook
//     carries σ_p from pixel to pixel (eqs. 8, 9) and re-renders where the allocation says.
// Fixed allocation needs none of this: uniform passes.
#pragma once

#include "render/scan_bands.h"
#include "techniques/two_stage/two_stage_integrator.h"

namespace rr::two_stage {

class TwoStageSchedule final : public RenderSchedule {
  public:
    TwoStageSchedule(TwoStageIntegrator& integrator, const ScheduleInputs& inputs);

    bool supportsTimeLimit() const override { return false; }
    uint64_t plannedSamples() const override { return uint64_t(width_) * height_ * spp_; }
    bool nextRound(const Film& film, const RoundTiming& timing, Round* round) override;
    void unitVisits(size_t unit, std::vector<PixelVisit>* visits) const override;
    std::unique_ptr<PixelRenderer> pixelRenderer(const Sampler& sampler) const override;

  private:
    enum class Stage : uint8_t { Start, Pilot, Bands, Done };

    TwoStageIntegrator& integrator_;
    const Scene& scene_;
    int width_, height_;
    uint32_t spp_;
    Stage stage_ = Stage::Start;
};

}  // namespace rr::two_stage
