// The metrics tool's EXR inputs. Every problem with an input file is a MetricsError naming it.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/exr_io.h"

namespace rr {

inline constexpr std::array<const char*, 3> kRgbChannels{"R", "G", "B"};

// The R, G, B channels of an image in double precision, all finite.
struct InputImage {
    std::string source;  // the file it came from, for messages
    int width = 0, height = 0;
    std::array<std::vector<double>, 3> channels;  // R, G, B: width·height values, row-major
    size_t pixels() const { return size_t(width) * height; }
};

// readExr, with a missing or unreadable file reported as a MetricsError.
ExrImage readInputExr(const std::filesystem::path& file);

// Throws when R, G or B is missing, or names the pixel (x, y) and channel of the first NaN or
// infinity; `source` names the image in the message.
InputImage inputFromExr(const ExrImage& exr, const std::string& source);

// Throws unless every value of `channel` is finite.
void checkFinite(const ExrImage& exr, const std::string& channel, const std::string& source);

// An int or double attribute as double; none when absent or of another type.
std::optional<double> numericAttribute(const ExrImage& exr, const std::string& name);

}  // namespace rr
