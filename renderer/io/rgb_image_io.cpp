#include "io/rgb_image_io.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cctype>
#include <memory>
#include <stdexcept>

#include "io/exr_io.h"

namespace rr {

namespace fs = std::filesystem;

namespace {

std::string lowercaseExtension(const fs::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

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

// stbi_loadf returns linear values for Radiance files (it would apply a display gamma to 8-bit
// formats, which is why only .hdr is routed here).
RgbImage readRadiance(const fs::path& file) {
    int width = 0, height = 0, components = 0;
    const std::unique_ptr<float, void (*)(void*)> data(
        stbi_loadf(file.c_str(), &width, &height, &components, 3), stbi_image_free);
    if (!data || !stbi_is_hdr(file.c_str()))
        throw std::runtime_error("cannot read Radiance HDR " + file.string() + ": " +
                                 (data ? "not a Radiance file" : stbi_failure_reason()));
    if (width < 1 || height < 1)  // stb accepts a header of 0 pixels across
        throw std::runtime_error("Radiance HDR " + file.string() + " has no pixels");
    RgbImage image{width, height, std::vector<Rgb>(size_t(width) * height)};
    const float* p = data.get();
    for (Rgb& pixel : image.pixels) {
        pixel = Rgb(p[0], p[1], p[2]);
        p += 3;
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
