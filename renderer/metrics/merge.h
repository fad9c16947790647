// Averaging independent renders of one scene into a reference image, with an estimate of the
// result's own noise when it is made of two equal halves.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "io/exr_io.h"

namespace rr {

// Noise of (A+B)/2 estimated from the difference of the two independent halves.
struct HalfDifferenceNoise {
    double halfDifferenceRmse = 0;           // RMS over all pixels and RGB channels of A − B
    double noiseRmse = 0;                    // halfDifferenceRmse / 2
    std::optional<double> noiseSigmaOverMu;  // noiseRmse / mean; none unless the mean is > 0
};

struct MergedReference {
    ExrImage image;
    std::optional<int> spp;  // sum of the inputs' renderer.spp when every input has it
    double mean = 0;         // over all pixels and RGB channels
    std::optional<HalfDifferenceNoise> noise;  // exactly two inputs of equal (or unknown) spp
};

// Weighted mean of R, G, B with weights proportional to renderer.spp (equal when an input lacks
// it), plus variance.R/G/B = Σ w² v when every input has them, and reference.* attributes.
// `names[i]` names inputs[i] in messages and in reference.sources. Throws MetricsError for
// fewer than 2 inputs, missing channels, NaN or infinite values, different sizes or a
// non-positive spp.
MergedReference mergeImages(const std::vector<ExrImage>& inputs,
                            const std::vector<std::string>& names);

}  // namespace rr
