// 8-bit sRGB PNG preview of a linear image: multiply by 2^exposure, apply the sRGB transfer
// curve, clamp. Encoded through libpng at a fast deflate level (a preview is for looking, not
// archiving: level 3 encodes a 512² image in ~20 ms, where the default takes ~32 ms and
// stb_image_write ~48 ms).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace rr {

// The PNG file's bytes. Encoding apart from writing lets the render command encode the
// preview while the EXR is compressed, and write it only once the EXR is in place.
std::vector<uint8_t> encodePngPreview(int width, int height, const std::vector<float>& r,
                                      const std::vector<float>& g, const std::vector<float>& b,
                                      float exposureStops);

// Writes the encoded preview atomically.
void writePngPreview(const std::filesystem::path& file, const std::vector<uint8_t>& png);

}  // namespace rr
