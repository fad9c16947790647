#include "io/png_preview.h"

#include <png.h>

#include <cmath>
#include <csetjmp>
#include <fstream>
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

struct PngSink {
    std::vector<uint8_t> bytes;
    bool failed = false;
};

void appendToSink(png_structp png, png_bytep data, png_size_t length) {
    auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
    try {
        sink->bytes.insert(sink->bytes.end(), data, data + length);
    } catch (...) {  // no exception may cross libpng's C frames
        sink->failed = true;
    }
}

// libpng reports errors by longjmp to the setjmp in this function, which owns no C++ object
// with a destructor: the caller owns the pixels and the sink.
bool encodeRgb8(int width, int height, const uint8_t* pixels, PngSink* sink) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    if (!png) return false;
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {  // a libpng error
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_set_write_fn(png, sink, appendToSink, nullptr);
    png_set_compression_level(png, 3);
    png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < height; ++y)
        png_write_row(png, pixels + size_t(y) * width * 3);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return !sink->failed;
}

}  // namespace

std::vector<uint8_t> encodePngPreview(int width, int height, const std::vector<float>& r,
                                      const std::vector<float>& g, const std::vector<float>& b,
                                      float exposureStops) {
    const float scale = std::exp2(exposureStops);
    std::vector<uint8_t> pixels(size_t(width) * height * 3);
    for (size_t i = 0; i < size_t(width) * height; ++i) {
        pixels[3 * i + 0] = encodeSrgb(r[i] * scale);
        pixels[3 * i + 1] = encodeSrgb(g[i] * scale);
        pixels[3 * i + 2] = encodeSrgb(b[i] * scale);
    }
    PngSink sink;
    if (!encodeRgb8(width, height, pixels.data(), &sink))
        throw std::runtime_error("cannot encode the PNG preview");
    return std::move(sink.bytes);
}

void writePngPreview(const std::filesystem::path& file, const std::vector<uint8_t>& png) {
    writeAtomically(file, [&](const std::filesystem::path& temporary) {
        std::ofstream stream(temporary, std::ios::binary);
        stream.write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
        stream.close();
        if (!stream) throw std::runtime_error("cannot write " + file.string());
    });
}

}  // namespace rr
