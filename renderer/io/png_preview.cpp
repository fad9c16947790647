#include "io/png_preview.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "io/atomic_write.h"

namespace rr {

namespace {

uint8_t encodeSrgb(float linear) {
    if (!(linear > 0)) return 0;  // also maps NaN to black
    const float v =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(std::min(v, 1.0f) * 255.0f));
}

}  // namespace

void writePngPreview(const std::filesystem::path& file, int width, int height,
                     const std::vector<float>& r, const std::vector<float>& g,
                     const std::vector<float>& b, float exposureStops) {
    const float scale = std::exp2(exposureStops);
    std::vector<uint8_t> pixels(size_t(width) * height * 3);
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        pixels[3 * i + 0] = encodeSrgb(r[i] * scale);
        pixels[3 * i + 1] = encodeSrgb(g[i] * scale);
        pixels[3 * i + 2] = encodeSrgb(b[i] * scale);
    }
    writeAtomically(file, [&](const std::filesystem::path& temporary) {
        auto out = OIIO::ImageOutput::create(temporary.string());
        if (!out) throw std::runtime_error("OpenImageIO cannot write " + file.string());
        const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
        if (!out->open(temporary.string(), spec) ||
            !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close())
            throw std::runtime_error("cannot write " + file.string() + ": " + out->geterror());
    });
}

}  // namespace rr
