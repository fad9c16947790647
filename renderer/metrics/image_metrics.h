// Error of a rendered image against a reference as the importance-sampling papers report it:
// MSE and RMSE; σ/µ, which the papers define as the RMSE over all pixels and RGB channels
// divided by the mean of the reference; relative MSE; and the perceptual tvi error of Lai et
// al. 2007. Each is given over RGB, per channel and on luminance. All in double precision.
#pragma once

#include <array>
#include <optional>

#include "math/tvi.h"
#include "metrics/input_images.h"

namespace rr {

struct CompareOptions {
    double relmseRejectFraction = 0;  // in [0, 0.5): share of pixels dropped from relMSE
    double cdPerUnit = kDefaultCdPerUnit;
};

struct ErrorStats {
    double mse = 0, rmse = 0;
    double referenceMean = 0;
    double mean = 0;                    // of the image, over the same values
    std::optional<double> sigmaOverMu;  // rmse / referenceMean; none unless that mean is > 0
    // mean / referenceMean − 1: the image's bias, when averaged over independent renders
    // (a biased technique's, e.g. TAIS's contribution filter); none unless referenceMean > 0.
    std::optional<double> relativeBias;
    // Mean of (x−r)²/(r²+0.01) over the pixels that remain after the rejection, each pixel
    // contributing the mean over its values.
    double relmse = 0;
    // Lai et al. 2007: (1/N) Σ_pixels e²/tvi(L), L the reference pixel's luminance and e the
    // difference, both in cd/m². e is the luminance difference for RGB and luminance, and the
    // channel difference per channel.
    double tviErr = 0;
};

struct Comparison {
    int width = 0, height = 0;
    ErrorStats rgb;  // over all pixels and the three channels
    std::array<ErrorStats, 3> channels;
    ErrorStats luminance;  // on Rec. 709 Y = 0.2126 R + 0.7152 G + 0.0722 B
};

// Throws MetricsError when the sizes differ, the reference's RGB mean is not positive, or an
// option is out of range.
Comparison compareImages(const InputImage& image, const InputImage& reference,
                         const CompareOptions& options = {});

// The papers' efficiency 1 / (seconds · error); none when the error is 0 (a perfect image has
// no finite efficiency) or so small that the efficiency overflows.
std::optional<double> efficiency(double error, double seconds);

}  // namespace rr
