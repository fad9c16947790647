#include "render/film.h"

namespace rr {

void Film::add(int x, int y, const Rgb& value) {
    Pixel& p = pixels_[size_t(y) * width_ + x];
    for (int c = 0; c < 3; ++c) {
        const double v = value[c];
        p.sum[c] += v;
        p.sumSquares[c] += v * v;
    }
    ++p.count;
}

Rgb Film::mean(int x, int y) const {
    const Pixel& p = pixel(x, y);
    if (p.count == 0) return Rgb(0.0f);
    const double n = p.count;
    return Rgb(float(p.sum[0] / n), float(p.sum[1] / n), float(p.sum[2] / n));
}

Rgb Film::varianceOfMean(int x, int y) const {
    const Pixel& p = pixel(x, y);
    if (p.count < 2) return Rgb(0.0f);
    const double n = p.count;
    float v[3];
    for (int c = 0; c < 3; ++c) {
        const double m = p.sum[c] / n;
        const double sampleVariance = (p.sumSquares[c] - n * m * m) / (n - 1);
        v[c] = static_cast<float>(sampleVariance > 0 ? sampleVariance / n : 0.0);
    }
    return Rgb(v[0], v[1], v[2]);
}

}  // namespace rr
