#include "sampling/distribution1d.h"

#include <algorithm>

#include "math/vector.h"

namespace rr {

Distribution1D::Distribution1D(std::span<const float> weights) {
    const size_t n = weights.size();
    double total = 0;
    for (float w : weights)
        total += w;
    pmf_.resize(n);
    cdf_.resize(n + 1);
    cdf_[0] = 0;
    for (size_t i = 0; i < n; ++i) {
        const double p = total > 0 ? weights[i] / total : 1.0 / static_cast<double>(n);
        pmf_[i] = static_cast<float>(p);
        cdf_[i + 1] = cdf_[i] + p;
    }
    if (n > 0) cdf_[n] = 1.0;
}

int Distribution1D::sample(float u, float* pmf, float* uRemapped) const {
    // Last i with cdf_[i] <= u, skipping zero-probability entries.
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), static_cast<double>(u));
    int i = std::clamp(static_cast<int>(it - cdf_.begin()) - 1, 0, size() - 1);
    while (pmf_[i] == 0 && i + 1 < size())
        ++i;
    if (pmf) *pmf = pmf_[i];
    if (uRemapped) {
        const double width = cdf_[i + 1] - cdf_[i];
        const double r = width > 0 ? (u - cdf_[i]) / width : 0.0;
        *uRemapped = std::min(static_cast<float>(r), kOneMinusEpsilon);
    }
    return i;
}

float Distribution1D::invert(int index, float uRemapped) const {
    const double u = cdf_[index] + double(uRemapped) * (cdf_[index + 1] - cdf_[index]);
    return std::min(static_cast<float>(u), kOneMinusEpsilon);
}

}  // namespace rr
