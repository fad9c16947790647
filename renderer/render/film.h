// Per-pixel accumulation of samples in double precision: sum and sum of squares per channel
// and a count, from which the mean and the variance of the mean follow. Each pixel is only
// ever written by one task, in sample order, so results are bit-identical across threads.
#pragma once

#include <cstdint>
#include <vector>

#include "math/rgb.h"

namespace rr {

class Film {
  public:
    Film(int width, int height) : width_(width), height_(height), pixels_(size_t(width) * height) {}

    void add(int x, int y, const Rgb& value);

    int width() const { return width_; }
    int height() const { return height_; }
    Rgb mean(int x, int y) const;
    // Sample variance / n: the variance of the pixel estimate (0 with fewer than 2 samples).
    Rgb varianceOfMean(int x, int y) const;
    uint32_t sampleCount(int x, int y) const { return pixel(x, y).count; }

  private:
    struct Pixel {
        double sum[3] = {0, 0, 0};
        double sumSquares[3] = {0, 0, 0};
        uint32_t count = 0;
    };
    const Pixel& pixel(int x, int y) const { return pixels_[size_t(y) * width_ + x]; }

    int width_, height_;
    std::vector<Pixel> pixels_;
};

}  // namespace rr
