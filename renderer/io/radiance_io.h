// Radiance RGBE (.hdr) images: the header (#?RADIANCE or #?RGBE, FORMAT=32-bit_rle_rgbe, the
// "-Y height +X width" resolution line) and flat or run-length encoded scanlines (Ward,
// "Real Pixels", Graphics Gems II). Written here rather than taken from stb_image: the copy
// Debian's libraries resolve stbi_loadf to loops forever on some malformed run lengths, which
// `make fuzz` found (tests/fuzz/regressions/hdr/). Values are those stb_image gives, bit for
// bit: a mantissa m with exponent e becomes m · 2^(e − 136) in float, 0 where e = 0.
#pragma once

#include <filesystem>

#include "io/rgb_image_io.h"

namespace rr {

// Throws std::runtime_error naming the file when it cannot be read or is malformed.
RgbImage readRadiance(const std::filesystem::path& file);

}  // namespace rr
