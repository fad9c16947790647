#include "render/scan_bands.h"

#include <algorithm>

namespace rr {

void serpentineVisits(int width, int y0, int y1, uint32_t first, uint32_t count, bool keep,
                      std::vector<PixelVisit>* visits) {
    for (int y = y0; y < y1; ++y) {
        const bool rightwards = (y - y0) % 2 == 0;
        for (int i = 0; i < width; ++i)
            visits->push_back({rightwards ? i : width - 1 - i, y, first, count, keep});
    }
}

ScanBands::ScanBands(int width, int height, uint32_t spp, int bandRows, int warmupRows,
                     HookFactory hooks)
    : width_(width),
      height_(height),
      spp_(spp),
      bandRows_(bandRows),
      warmupRows_(warmupRows),
      hooks_(std::move(hooks)) {}

bool ScanBands::nextRound(const Film&, const RoundTiming&, Round* round) {
    if (started_) return false;
    started_ = true;
    *round = Round{size_t((height_ + bandRows_ - 1) / bandRows_), /*interruptible=*/true};
    return true;
}

void ScanBands::unitVisits(size_t unit, std::vector<PixelVisit>* visits) const {
    visits->clear();
    const int y0 = static_cast<int>(unit) * bandRows_, y1 = std::min(y0 + bandRows_, height_);
    const int start = y0 - std::min(warmupRows_, y0);
    // The warm-up rows and the band are one serpentine scan: the band's first row continues
    // in the direction the warm-up left off.
    serpentineVisits(width_, start, y1, 0, spp_, true, visits);
    for (PixelVisit& v : *visits)
        if (v.y < y0) v = PixelVisit{v.x, v.y, spp_, spp_, false};
}

}  // namespace rr
