// Reading colour images for textures and environment maps: OpenEXR (channels R, G, B, or a
// single Y as grey) through exr_io, and Radiance RGBE (.hdr) through radiance_io.
#pragma once

#include <filesystem>
#include <vector>

#include "math/rgb.h"

namespace rr {

struct RgbImage {
    int width = 0, height = 0;
    std::vector<Rgb> pixels;  // width·height, row-major, top row first
};

// Chooses the format by extension (.exr or .hdr, any case). Throws std::runtime_error naming
// the file when it cannot be read, has another extension, or holds no colour channels.
RgbImage readRgbImage(const std::filesystem::path& file);

}  // namespace rr
