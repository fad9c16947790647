// Fixed bands of rows, each scanned by one unit in serpentine order (the band's first row left
// to right, the next right to left, and so on), every pixel getting `spp` samples: for
// techniques whose pixels learn from the pixels rendered before them (TAIS, Cline et al. 2008
// §3.3: "we scan back and forth to allow importance to propagate both left and right, as well
// as down"). Bands are fixed by the settings, never by the thread count, so the image is the
// same for any number of threads. A band may first scan `warmupRows` rows of the band above
// with sample indices spp … 2 spp − 1, independent of the samples the image keeps, and discard
// them (keep = false), so that it does not start learning from nothing. One round renders the
// whole image; a cancelled render stops between bands and leaves the image incomplete.
#pragma once

#include <functional>

#include "render/render_schedule.h"

namespace rr {

// Rows [y0, y1) of an image `width` pixels wide in serpentine order, `first` and `count` the
// sample range of every visit.
void serpentineVisits(int width, int y0, int y1, uint32_t first, uint32_t count, bool keep,
                      std::vector<PixelVisit>* visits);

class ScanBands final : public RenderSchedule {
  public:
    using HookFactory = std::function<std::unique_ptr<PixelRenderer>(const Sampler&)>;

    ScanBands(int width, int height, uint32_t spp, int bandRows, int warmupRows, HookFactory hooks);

    bool supportsTimeLimit() const override { return false; }
    uint64_t plannedSamples() const override { return uint64_t(width_) * height_ * spp_; }
    bool nextRound(const Film& film, const RoundTiming& timing, Round* round) override;
    void unitVisits(size_t unit, std::vector<PixelVisit>* visits) const override;
    std::unique_ptr<PixelRenderer> pixelRenderer(const Sampler& sampler) const override {
        return hooks_(sampler);
    }

  private:
    int width_, height_;
    uint32_t spp_;
    int bandRows_, warmupRows_;
    HookFactory hooks_;
    bool started_ = false;
};

}  // namespace rr
