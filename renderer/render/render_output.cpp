#include "render/render_output.h"

namespace rr {

ExrImage filmToExr(const Film& film) {
    ExrImage image;
    image.width = film.width();
    image.height = film.height();
    const size_t n = size_t(image.width) * image.height;
    for (const char* name : {"R", "G", "B", "variance.R", "variance.G", "variance.B", "samples"})
        image.channels[name].resize(n);
    auto& ch = image.channels;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const size_t i = size_t(y) * image.width + x;
            const Rgb m = film.mean(x, y), v = film.varianceOfMean(x, y);
            ch["R"][i] = m.r;
            ch["G"][i] = m.g;
            ch["B"][i] = m.b;
            ch["variance.R"][i] = v.r;
            ch["variance.G"][i] = v.g;
            ch["variance.B"][i] = v.b;
            ch["samples"][i] = static_cast<float>(film.sampleCount(x, y));
        }
    return image;
}

}  // namespace rr
