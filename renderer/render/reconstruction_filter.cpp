#include "render/reconstruction_filter.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rr {

const char* filterName(FilterType type) {
    switch (type) {
        case FilterType::Box:
            return "box";
        case FilterType::Mitchell:
            return "mitchell";
        case FilterType::Gaussian:
            return "gaussian";
    }
    return "?";
}

ReconstructionFilter::ReconstructionFilter(const FilterSettings& settings) : settings_(settings) {
    if (isBox()) return;
    const double r = settings_.radius;
    if (!(r >= 0.5 && r <= kMaxRadius))
        throw std::logic_error("a filter's radius must lie in [0.5, 8] pixels");
    reach_ = static_cast<int>(std::ceil(r + 0.5)) - 1;
    if (settings_.type == FilterType::Mitchell) {
        const double B = settings_.b, C = settings_.c;
        scale_ = 2 / r;
        // Mitchell & Netravali 1988, divided by 6: x³, x², x, 1.
        const double inner[4] = {12 - 9 * B - 6 * C, -18 + 12 * B + 6 * C, 0, 6 - 2 * B};
        const double outer[4] = {-B - 6 * C, 6 * B + 30 * C, -12 * B - 48 * C, 8 * B + 24 * C};
        for (int i = 0; i < 4; ++i) {
            inner_[i] = inner[i] / 6;
            outer_[i] = outer[i] / 6;
        }
    }
    if (settings_.type == FilterType::Gaussian) {
        gaussianTail_ = std::exp(-settings_.alpha * r * r);
        gaussianNorm_ = 2 * gaussianArea(r);
    }
}

// Mitchell & Netravali 1988: the cubic with parameters B and C on [0, 2), which integrates to
// ½ over [0, 2].
double ReconstructionFilter::mitchell(double x) const {
    const double* k = x < 1 ? inner_ : outer_;
    return x < 2 ? ((k[0] * x + k[1]) * x + k[2]) * x + k[3] : 0.0;
}

double ReconstructionFilter::mitchellArea(double x) const {
    auto area = [](const double* k, double t) {
        return (((k[0] / 4 * t + k[1] / 3) * t + k[2] / 2) * t + k[3]) * t;
    };
    if (x < 1) return area(inner_, x);
    return area(inner_, 1) + area(outer_, std::min(x, 2.0)) - area(outer_, 1);
}

double ReconstructionFilter::gaussianArea(double d) const {
    const double a = settings_.alpha;
    return 0.5 * std::sqrt(std::numbers::pi / a) * std::erf(d * std::sqrt(a)) - d * gaussianTail_;
}

double ReconstructionFilter::weight1D(double d) const {
    const double r = settings_.radius;
    switch (settings_.type) {
        case FilterType::Box:
            return d >= -0.5 && d < 0.5 ? 1.0 : 0.0;
        case FilterType::Mitchell:
            return scale_ * mitchell(scale_ * std::abs(d));
        case FilterType::Gaussian:
            return std::abs(d) < r
                       ? (std::exp(-settings_.alpha * d * d) - gaussianTail_) / gaussianNorm_
                       : 0.0;
    }
    return 0;
}

double ReconstructionFilter::integral1D(double a, double b) const {
    const double r = settings_.radius;
    // An antiderivative of weight1D, odd and constant outside the support.
    auto area = [&](double d) -> double {
        switch (settings_.type) {
            case FilterType::Box:
                return std::clamp(d, -0.5, 0.5);
            case FilterType::Mitchell:
                return std::copysign(mitchellArea(std::min(scale_ * std::abs(d), 2.0)), d);
            case FilterType::Gaussian:
                return gaussianArea(std::clamp(d, -r, r)) / gaussianNorm_;
        }
        return 0;
    };
    return area(b) - area(a);
}

void ReconstructionFilter::taps(float offset, Taps* taps) const {
    if (isBox()) {
        taps->first = taps->last = 0;
        taps->weight[0] = 1;
        return;
    }
    // Tap i is the centre of pixel (own − reach + i), at −reach + i + ½ from the own pixel's
    // corner; the sample lies at d_i = offset + reach − i − ½ from it. Taps outside the
    // radius are 0; first and last bound the others. One loop per type: this runs twice per
    // sample a splatting film takes.
    const double centre = double(offset) + reach_ - 0.5, r = settings_.radius;
    const int n = 2 * reach_ + 1;
    taps->first = n;
    taps->last = -1;
    const bool isMitchell = settings_.type == FilterType::Mitchell;
    for (int i = 0; i < n; ++i) {
        const double d = centre - i;
        const bool inside = std::abs(d) < r;
        taps->weight[size_t(i)] = isMitchell ? scale_ * mitchell(scale_ * std::abs(d))
                                  : inside   ? weight1D(d)
                                             : 0.0;
        if (inside) {
            taps->first = std::min(taps->first, i);
            taps->last = i;
        }
    }
}

nlohmann::json ReconstructionFilter::parameters() const {
    nlohmann::json p;
    p["type"] = filterName(settings_.type);
    if (settings_.type == FilterType::Mitchell) {
        p["radius"] = settings_.radius;
        p["b"] = settings_.b;
        p["c"] = settings_.c;
    } else if (settings_.type == FilterType::Gaussian) {
        p["radius"] = settings_.radius;
        p["alpha"] = settings_.alpha;
    }
    return p;
}

}  // namespace rr
