// Float EXR files with named channels and string/int/double metadata (OpenEXR, ZIP).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <variant>
#include <vector>

namespace rr {

using ExrAttributeValue = std::variant<std::string, int, double>;

struct ExrImage {
    int width = 0, height = 0;
    std::map<std::string, std::vector<float>> channels;  // name -> width·height values, row-major
    std::map<std::string, ExrAttributeValue> attributes;
};

// Writes atomically (temporary file + rename).
void writeExr(const std::filesystem::path& file, const ExrImage& image);
// Reads every float/half/uint channel as float, and the string/int/float/double attributes.
// Throws std::runtime_error naming the file when it cannot be read.
ExrImage readExr(const std::filesystem::path& file);

}  // namespace rr
