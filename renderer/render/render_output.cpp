#include "render/render_output.h"

#include <stdexcept>

namespace rr {

ExrImage filmToExr(const Film& film, const std::vector<Rgb>& estimates) {
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
    if (!estimates.empty() && estimates.size() != n)
        throw std::logic_error("pixel estimates must give one value per pixel");
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const size_t i = size_t(y) * image.width + x;
            const Rgb m = estimates.empty() ? film.mean(x, y) : estimates[i];
            const Rgb v = film.varianceOfMean(x, y);
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
