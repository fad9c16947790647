#include "scene/lights/latlong_resampling.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace rr {

namespace {

constexpr int kSubSamples = 2;  // per axis

// The texel of `image` that `st` falls in, black where `from` gives it no solid angle.
Rgb nearestTexel(const RgbImage& image, const EnvLayout& from, Vec2 st) {
    const int col = std::clamp(static_cast<int>(st.x * float(image.width)), 0, image.width - 1);
    const int row = std::clamp(static_cast<int>(st.y * float(image.height)), 0, image.height - 1);
    const Vec2 centre((float(col) + 0.5f) / float(image.width),
                      (float(row) + 0.5f) / float(image.height));
    if (!(from.jacobian(centre) > 0)) return Rgb(0.0f);
    const Rgb& p = image.pixels[size_t(row) * image.width + col];
    return Rgb(std::max(p.r, 0.0f), std::max(p.g, 0.0f), std::max(p.b, 0.0f));
}

}  // namespace

RgbImage resampleToLatLong(const RgbImage& image, const EnvLayout& from, int width) {
    RgbImage out;
    out.width = width;
    out.height = width / 2;
    out.pixels.assign(size_t(out.width) * out.height, Rgb(0.0f));
    const LatLongLayout latLong;
    tbb::parallel_for(0, out.height, [&](int row) {
        for (int col = 0; col < out.width; ++col) {
            Rgb sum(0.0f);
            for (int a = 0; a < kSubSamples; ++a)
                for (int b = 0; b < kSubSamples; ++b) {
                    const Vec2 st(
                        (float(col) + (float(a) + 0.5f) / kSubSamples) / float(width),
                        (float(row) + (float(b) + 0.5f) / kSubSamples) / float(out.height));
                    Vec3 w;
                    float jacobian;
                    latLong.direction(st, &w, &jacobian);
                    sum += nearestTexel(image, from, from.imagePoint(w));
                }
            out.pixels[size_t(row) * width + col] = sum * (1.0f / (kSubSamples * kSubSamples));
        }
    });
    return out;
}

}  // namespace rr
