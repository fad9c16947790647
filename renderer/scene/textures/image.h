// Image texture: bilinear interpolation between texel centres, repeating in both directions.
// u runs to the right and v upwards: texel row 0 (the image's top row) is at v = 1 and the
// bottom row at v = 0. Texel (i, j) has its centre at ((i + ½)/w, 1 − (j + ½)/h).
#pragma once

#include <cmath>
#include <vector>

#include "scene/texture.h"

namespace rr {

template <class T>
class ImageTexture final : public Texture<T> {
  public:
    // `texels`: width·height values, row-major, top row first.
    ImageTexture(int width, int height, std::vector<T> texels)
        : width_(width), height_(height), texels_(std::move(texels)) {}

    T eval(const ShadingContext& ctx) const override {
        // Continuous texel coordinates, with texel centres at integers.
        const double x = repeat(ctx.uv.x) * width_ - 0.5;
        const double y = (1.0 - repeat(ctx.uv.y)) * height_ - 0.5;
        const double x0 = std::floor(x), y0 = std::floor(y);
        const float fx = float(x - x0), fy = float(y - y0);
        const int i0 = wrap(int(x0), width_), i1 = wrap(int(x0) + 1, width_);
        const int j0 = wrap(int(y0), height_), j1 = wrap(int(y0) + 1, height_);
        const T top = texel(i0, j0) * (1.0f - fx) + texel(i1, j0) * fx;
        const T bottom = texel(i0, j1) * (1.0f - fx) + texel(i1, j1) * fx;
        return top * (1.0f - fy) + bottom * fy;  // convex: stays within the texels' range
    }

  private:
    // The fractional part in [0, 1]; non-finite coordinates (never produced by the shapes)
    // read the texel at the origin rather than overflow the index conversion.
    static double repeat(float t) {
        if (!std::isfinite(t)) return 0;
        return double(t) - std::floor(double(t));
    }
    static int wrap(int i, int n) { return ((i % n) + n) % n; }
    const T& texel(int i, int j) const { return texels_[size_t(j) * width_ + i]; }

    int width_, height_;
    std::vector<T> texels_;
};

}  // namespace rr
