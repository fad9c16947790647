// Reconstruction filters: how much a sample at film position u counts towards the pixel whose
// centre is c, w(u − c), a product of two 1-D weights. pbrt-v1, which the TAIS, two-stage and
// PMC papers extended, splats every sample to each pixel centre within the filter's radius and
// writes Σ w·L / Σ w (`film/image.cpp`), with the Mitchell–Netravali filter of radius 2 and
// B = C = 1/3 by default (`core/api.cpp`, `filters/mitchell.cpp`). Our default is the box: a
// pixel is the mean of its own samples, and nothing is splatted.
//
// The 1-D weights are normalised so that each integrates to 1 over the line; pbrt-v1's Mitchell
// filter of radius 2 is this function exactly, and any other radius differs by a constant
// factor, which Σ w·L / Σ w cancels. A normalised filter lets an estimator that knows its
// sampling density use Σ w·L / q without dividing by Σ w (PMC-IP's unbiased image). pbrt-v1's
// film differs in two details we do not copy: it looks weights up in a 16 × 16 table of the
// filter at cell centres (we evaluate it), and it clamps a pixel's negative channels to 0 when
// writing (we keep the signed estimate: a clamp would bias it, and our references are formed
// the same way).
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>

namespace rr {

enum class FilterType : uint8_t { Box, Mitchell, Gaussian };

struct FilterSettings {
    FilterType type = FilterType::Box;
    double radius = 2;                // Mitchell and Gaussian: half-width in pixels
    double b = 1.0 / 3, c = 1.0 / 3;  // Mitchell–Netravali's B and C
    double alpha = 2;                 // Gaussian: exp(−α d²), less its value at the radius
};

class ReconstructionFilter {
  public:
    static constexpr double kMaxRadius = 8;
    // Pixels on either side of a sample's own pixel that its splat can reach, at most.
    static constexpr int kMaxReach = 8;
    static constexpr int kMaxTaps = 2 * kMaxReach + 1;

    ReconstructionFilter() = default;  // the box
    explicit ReconstructionFilter(const FilterSettings& settings);

    const FilterSettings& settings() const { return settings_; }
    bool isBox() const { return settings_.type == FilterType::Box; }
    // Pixels on either side of its own that a sample reaches: ⌈r + ½⌉ − 1 (0 for the box).
    int reach() const { return reach_; }

    // The normalised 1-D weight at offset d (in pixels) from a pixel centre. The box is 1 on
    // its own pixel, [−½, ½).
    double weight1D(double d) const;
    // ∫_a^b weight1D(d) dd, exactly (closed forms).
    double integral1D(double a, double b) const;

    // The weights one axis of a sample gives: the sample lies at `pixel` + `offset` (offset in
    // [0, 1)); weight[i] is the weight of the pixel centre pixel − reach() + i + ½, for
    // i < 2 reach() + 1, and only [first, last] can be non-zero (the centres within the
    // radius), so a splat needs no test per tap.
    struct Taps {
        std::array<double, kMaxTaps> weight;
        int first = 0, last = 0;
    };
    void taps(float offset, Taps* taps) const;

    // The settings as written in the output metadata (and read back by the loader).
    nlohmann::json parameters() const;

  private:
    double mitchell(double x) const;      // Mitchell–Netravali's cubic at x = 2|d|/r ∈ [0, 2)
    double mitchellArea(double x) const;  // ∫_0^x of it, x ∈ [0, 2]
    double gaussianArea(double d) const;  // ∫_0^d of the unnormalised Gaussian, |d| ≤ r

    FilterSettings settings_;
    int reach_ = 0;
    double scale_ = 1;                      // Mitchell: 2 / r, from d to the cubic's x
    double inner_[4] = {}, outer_[4] = {};  // the cubic's coefficients on [0, 1) and [1, 2)
    double gaussianTail_ = 0;               // exp(−α r²)
    double gaussianNorm_ = 1;               // ∫ of the unnormalised Gaussian over [−r, r]
};

const char* filterName(FilterType type);

}  // namespace rr
