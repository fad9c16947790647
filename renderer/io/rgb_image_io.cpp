#include "io/rgb_image_io.h"

#include <memory>
#include <stdexcept>

#include "io/exr_io.h"
#include "io/file_extension.h"
#include "io/radiance_io.h"

namespace rr {

namespace fs = std::filesystem;

namespace {

RgbImage readExrColour(const fs::path& file) {
    ExrImage exr = readExr(file);
    RgbImage image{exr.width, exr.height, std::vector<Rgb>(size_t(exr.width) * exr.height)};
    auto channel = [&](const char* name) -> const std::vector<float>* {
        const auto it = exr.channels.find(name);
        return it == exr.channels.end() ? nullptr : &it->second;
    };
    const std::vector<float>*r = channel("R"), *g = channel("G"), *b = channel("B");
    if (r && g && b) {
        for (size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = Rgb((*r)[i], (*g)[i], (*b)[i]);
    } else if (const std::vector<float>* y = channel("Y")) {
        for (size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = Rgb((*y)[i]);
    } else {
        throw std::runtime_error("EXR " + file.string() + " has neither R, G, B nor Y channels");
    }
    return image;
}

}  // namespace

RgbImage readRgbImage(const fs::path& file) {
    const std::string extension = lowercaseExtension(file);
    if (extension == ".exr") return readExrColour(file);
    if (extension == ".hdr") return readRadiance(file);
    throw std::runtime_error("unsupported image format " + file.string() +
                             " (expected .exr or .hdr)");
}

}  // namespace rr
