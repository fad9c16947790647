#include "metrics/input_images.h"

#include <cmath>

#include "metrics/metrics_error.h"

namespace rr {

ExrImage readInputExr(const std::filesystem::path& file) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw MetricsError("cannot read " + file.string() + ": no such file");
    try {
        return readExr(file);
    } catch (const std::runtime_error& e) {  // readExr's message names the file and the cause
        throw MetricsError(e.what());
    }
}

void checkFinite(const ExrImage& exr, const std::string& channel, const std::string& source) {
    const std::vector<float>& values = exr.channels.at(channel);
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
            throw MetricsError(source + ": " + (std::isnan(values[i]) ? "NaN" : "infinite") +
                               " value in channel " + channel + " at pixel (" +
                               std::to_string(i % exr.width) + ", " +
                               std::to_string(i / exr.width) + ")");
}

InputImage inputFromExr(const ExrImage& exr, const std::string& source) {
    InputImage image{source, exr.width, exr.height, {}};
    for (size_t c = 0; c < 3; ++c) {
        const auto it = exr.channels.find(kRgbChannels[c]);
        if (it == exr.channels.end())
            throw MetricsError(source + ": no channel " + kRgbChannels[c] +
                               " (R, G and B are required)");
        checkFinite(exr, kRgbChannels[c], source);
        image.channels[c].assign(it->second.begin(), it->second.end());
    }
    return image;
}

std::optional<double> numericAttribute(const ExrImage& exr, const std::string& name) {
    const auto it = exr.attributes.find(name);
    if (it == exr.attributes.end()) return std::nullopt;
    if (const auto* i = std::get_if<int>(&it->second)) return double(*i);
    if (const auto* d = std::get_if<double>(&it->second)) return *d;
    return std::nullopt;
}

}  // namespace rr
