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

// Writes atomically (temporary file + rename). ZIP compresses blocks of 16 rows independently,
// so `threads` threads compress them in parallel (a 512² render's seven float channels: 137 ms
// on one thread, 78 ms on two).
void writeExr(const std::filesystem::path& file, const ExrImage& image, int threads = 1);
// Reads every float/half/uint channel as float, and the string/int/float/double attributes.
// Throws std::runtime_error naming the file when it cannot be read.
ExrImage readExr(const std::filesystem::path& file);

}  // namespace rr
