#include "sampling/distribution1d.h"

#include <algorithm>

#include "math/vector.h"

namespace rr {

Distribution1D::Distribution1D(std::span<const float> weights) {
    const size_t n = weights.size();
    double total = 0;
    for (float w : weights)
        total += w;
    entries_.assign(n + 1, Entry{0, 0, 0});
    for (size_t i = 0; i < n; ++i) {
        const double p = total > 0 ? weights[i] / total : 1.0 / static_cast<double>(n);
        entries_[i].pmf = static_cast<float>(p);
        entries_[i + 1].cdf = entries_[i].cdf + p;
    }
    if (n > 0) entries_[n].cdf = 1.0;
    size_t last = 0;
    for (size_t k = 0; k < n; ++k) {
        const double start = double(k) / double(n);
        while (last + 1 < n && entries_[last + 1].cdf <= start)
            ++last;
        entries_[k].guide = static_cast<uint32_t>(last);
    }
}

int Distribution1D::sample(float u, float* pmf, float* uRemapped) const {
    // The last i with cdf_i ≤ u, then past zero-probability entries. u·n is exact in double
    // (24-bit u, n < 2^29), so the slice's start ⌊u·n⌋/n is at most u.
    const size_t n = entries_.size() - 1;
    const double x = static_cast<double>(u);
    const size_t slice = std::min(static_cast<size_t>(std::max(x, 0.0) * double(n)), n - 1);
    size_t i = entries_[slice].guide;
    while (i + 1 < n && entries_[i + 1].cdf <= x)
        ++i;
    while (entries_[i].pmf == 0 && i + 1 < n)
        ++i;
    if (pmf) *pmf = entries_[i].pmf;
    if (uRemapped) {
        const double width = entries_[i + 1].cdf - entries_[i].cdf;
        const double r = width > 0 ? (x - entries_[i].cdf) / width : 0.0;
        *uRemapped = std::min(static_cast<float>(r), kOneMinusEpsilon);
    }
    return static_cast<int>(i);
}

float Distribution1D::invert(int index, float uRemapped) const {
    const Entry& e = entries_[size_t(index)];
    const double u = e.cdf + double(uRemapped) * (entries_[size_t(index) + 1].cdf - e.cdf);
    return std::min(static_cast<float>(u), kOneMinusEpsilon);
}

}  // namespace rr
