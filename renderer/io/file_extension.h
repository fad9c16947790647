// A file's extension in lower case (".exr", ".ply"): readers choose the format by it.
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace rr {

inline std::string lowercaseExtension(const std::filesystem::path& file) {
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

}  // namespace rr
