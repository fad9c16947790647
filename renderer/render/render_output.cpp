#include "render/render_output.h"

#include <stdexcept>

namespace rr {

ExrImage filmToExr(const Film& film, const PixelEstimates& estimates) {
    ExrImage image;
    image.width = film.width();
    image.height = film.height();
    const size_t n = size_t(image.width) * image.height;
    auto channel = [&](const char* name) -> float* {
        std::vector<float>& c = image.channels[name];
        c.resize(n);
        return c.data();
    };
    float *r = channel("R"), *g = channel("G"), *b = channel("B");
    float *vr = channel("variance.R"), *vg = channel("variance.G"), *vb = channel("variance.B");
    float* samples = channel("samples");
    const bool own = !estimates.values.empty();
    if (own && (estimates.values.size() != n || estimates.variances.size() != n))
        throw std::logic_error("pixel estimates must give one value and variance per pixel");
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const size_t i = size_t(y) * image.width + x;
            const Rgb m = own ? estimates.values[i] : film.mean(x, y);
            const Rgb v = own ? estimates.variances[i] : film.varianceOfMean(x, y);
            r[i] = m.r;
            g[i] = m.g;
            b[i] = m.b;
            vr[i] = v.r;
            vg[i] = v.g;
            vb[i] = v.b;
            samples[i] = static_cast<float>(film.sampleCount(x, y));
        }
    return image;
}

}  // namespace rr
