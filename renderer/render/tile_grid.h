// The image cut into 16×16 tiles, numbered row-major: the units of work of the schedules whose
// pixels are independent within a round.
#pragma once

#include <algorithm>
#include <cstddef>

namespace rr {

class TileGrid {
  public:
    TileGrid(int width, int height)
        : width_(width),
          height_(height),
          tilesX_((width + kTileSize - 1) / kTileSize),
          tilesY_((height + kTileSize - 1) / kTileSize) {}

    size_t tiles() const { return size_t(tilesX_) * tilesY_; }
    int width() const { return width_; }
    int height() const { return height_; }
    // Calls f(x, y) for the pixels of `tile`, row by row.
    template <class F>
    void forEachPixel(size_t tile, F&& f) const {
        const int t = static_cast<int>(tile);
        const int x0 = (t % tilesX_) * kTileSize, y0 = (t / tilesX_) * kTileSize;
        const int x1 = std::min(x0 + kTileSize, width_), y1 = std::min(y0 + kTileSize, height_);
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                f(x, y);
    }

  private:
    static constexpr int kTileSize = 16;
    int width_, height_, tilesX_, tilesY_;
};

}  // namespace rr
