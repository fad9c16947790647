#include "support/maps.h"

#include "io/exr_io.h"

namespace rr::test {

std::filesystem::path writeRgbExr(const std::filesystem::path& file, int width, int height,
                                  const PixelFunction& pixel) {
    ExrImage exr;
    exr.width = width;
    exr.height = height;
    for (const char* c : {"R", "G", "B"})
        exr.channels[c].resize(size_t(width) * height);
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const Rgb p = pixel(col, row);
            const size_t i = size_t(row) * width + col;
            exr.channels["R"][i] = p.r;
            exr.channels["G"][i] = p.g;
            exr.channels["B"][i] = p.b;
        }
    writeExr(file, exr);
    return file;
}

}  // namespace rr::test
