#include "metrics/merge.h"

#include <climits>
#include <cmath>

#include "metrics/input_images.h"
#include "metrics/metrics_error.h"

namespace rr {

namespace {

constexpr std::array<const char*, 3> kVarianceChannels{"variance.R", "variance.G", "variance.B"};

struct Weights {
    std::vector<double> w;
    std::optional<int> totalSpp;
};

// Proportional to renderer.spp, so every sample counts equally; equal when any input lacks it.
Weights sppWeights(const std::vector<ExrImage>& inputs, const std::vector<std::string>& names) {
    const size_t n = inputs.size();
    std::vector<double> spp;
    for (size_t i = 0; i < n; ++i) {
        const std::optional<double> s = numericAttribute(inputs[i], "renderer.spp");
        if (!s) continue;
        if (!(*s > 0 && *s <= INT_MAX))
            throw MetricsError(names[i] + ": renderer.spp is " + messageNumber(*s) +
                               ", not a positive sample count");
        spp.push_back(*s);
    }
    if (spp.size() < n) return {std::vector<double>(n, 1.0 / double(n)), std::nullopt};
    double total = 0;
    for (double s : spp)
        total += s;
    if (total > INT_MAX)
        throw MetricsError("the inputs' total spp " + messageNumber(total) +
                           " does not fit the int attribute reference.spp");
    Weights weights{{}, int(std::lround(total))};
    for (double s : spp)
        weights.w.push_back(s / total);
    return weights;
}

std::vector<InputImage> checkedRgb(const std::vector<ExrImage>& inputs,
                                   const std::vector<std::string>& names) {
    if (inputs.size() < 2)
        throw MetricsError("merge needs at least 2 images, got " + std::to_string(inputs.size()));
    std::vector<InputImage> rgb;
    for (size_t i = 0; i < inputs.size(); ++i) {
        rgb.push_back(inputFromExr(inputs[i], names[i]));
        if (rgb[i].width != rgb[0].width || rgb[i].height != rgb[0].height)
            throw MetricsError(names[i] + " is " + std::to_string(rgb[i].width) + "x" +
                               std::to_string(rgb[i].height) + " but " + names[0] + " is " +
                               std::to_string(rgb[0].width) + "x" + std::to_string(rgb[0].height));
    }
    return rgb;
}

// True when every input has every variance channel, all finite.
bool checkedVariance(const std::vector<ExrImage>& inputs, const std::vector<std::string>& names) {
    for (const ExrImage& input : inputs)
        for (const char* c : kVarianceChannels)
            if (!input.channels.count(c)) return false;
    for (size_t i = 0; i < inputs.size(); ++i)
        for (const char* c : kVarianceChannels)
            checkFinite(inputs[i], c, names[i]);
    return true;
}

// For independent halves of equal variance σ², Var(A − B) = 2σ² while Var((A + B)/2) = σ²/2:
// the merged image's noise is a quarter of the difference's variance, half its RMS.
HalfDifferenceNoise halfDifferenceNoise(const InputImage& a, const InputImage& b, double mean) {
    double squared = 0;
    for (size_t c = 0; c < 3; ++c)
        for (size_t p = 0; p < a.pixels(); ++p) {
            const double d = a.channels[c][p] - b.channels[c][p];
            squared += d * d;
        }
    HalfDifferenceNoise noise;
    noise.halfDifferenceRmse = std::sqrt(squared / (3.0 * double(a.pixels())));
    noise.noiseRmse = noise.halfDifferenceRmse / 2;
    if (mean > 0) noise.noiseSigmaOverMu = noise.noiseRmse / mean;
    return noise;
}

void addAttributes(const std::vector<ExrImage>& inputs, const std::vector<std::string>& names,
                   MergedReference* merged) {
    auto& a = merged->image.attributes;
    std::string sources;
    for (const std::string& name : names)
        sources += (sources.empty() ? "" : ",") + name;
    a["reference.sources"] = sources;
    if (merged->spp) a["reference.spp"] = *merged->spp;
    double renderTime = 0;
    size_t timed = 0;
    for (const ExrImage& input : inputs)
        if (const auto t = numericAttribute(input, "renderer.renderTime")) {
            renderTime += *t;
            ++timed;
        }
    if (timed == inputs.size()) a["reference.renderTime"] = renderTime;
    for (const char* key : {"renderer.integrator", "renderer.integratorParameters",
                            "renderer.sceneSha256", "renderer.version"})
        if (const auto it = inputs[0].attributes.find(key); it != inputs[0].attributes.end())
            a[key] = it->second;
    if (merged->noise) {
        a["reference.noiseRmse"] = merged->noise->noiseRmse;
        if (merged->noise->noiseSigmaOverMu)
            a["reference.noiseSigmaOverMu"] = *merged->noise->noiseSigmaOverMu;
    }
}

}  // namespace

MergedReference mergeImages(const std::vector<ExrImage>& inputs,
                            const std::vector<std::string>& names) {
    const std::vector<InputImage> rgb = checkedRgb(inputs, names);
    const bool variance = checkedVariance(inputs, names);
    const Weights weights = sppWeights(inputs, names);
    const size_t pixels = rgb[0].pixels();

    MergedReference merged;
    merged.spp = weights.totalSpp;
    merged.image.width = rgb[0].width;
    merged.image.height = rgb[0].height;
    double sum = 0;
    for (size_t c = 0; c < 3; ++c) {
        std::vector<float>& out = merged.image.channels[kRgbChannels[c]];
        out.resize(pixels);
        for (size_t p = 0; p < pixels; ++p) {
            double m = 0;
            for (size_t i = 0; i < rgb.size(); ++i)
                m += weights.w[i] * rgb[i].channels[c][p];
            out[p] = float(m);
            sum += m;
        }
    }
    merged.mean = sum / (3.0 * double(pixels));
    if (variance)
        for (const char* c : kVarianceChannels) {
            std::vector<float>& out = merged.image.channels[c];
            out.resize(pixels);
            for (size_t p = 0; p < pixels; ++p) {
                double v = 0;
                for (size_t i = 0; i < inputs.size(); ++i)
                    v += weights.w[i] * weights.w[i] * inputs[i].channels.at(c)[p];
                out[p] = float(v);
            }
        }
    if (rgb.size() == 2 && weights.w[0] == weights.w[1])
        merged.noise = halfDifferenceNoise(rgb[0], rgb[1], merged.mean);
    addAttributes(inputs, names, &merged);
    return merged;
}

}  // namespace rr
