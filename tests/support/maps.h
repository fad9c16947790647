// Small environment maps written for tests: an RGB OpenEXR image of a pixel function.
#pragma once

#include <filesystem>
#include <functional>

#include "math/rgb.h"

namespace rr::test {

using PixelFunction = std::function<Rgb(int col, int row)>;

// Writes `file` (width × height, row 0 the top row) and returns it.
std::filesystem::path writeRgbExr(const std::filesystem::path& file, int width, int height,
                                  const PixelFunction& pixel);

}  // namespace rr::test
