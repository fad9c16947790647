// 8-bit sRGB PNG preview of a linear image: multiply by 2^exposure, apply the sRGB transfer
// curve, clamp. Written through OpenImageIO, atomically.
#pragma once

#include <filesystem>
#include <vector>

namespace rr {

void writePngPreview(const std::filesystem::path& file, int width, int height,
                     const std::vector<float>& r, const std::vector<float>& g,
                     const std::vector<float>& b, float exposureStops);

}  // namespace rr
