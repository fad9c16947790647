#include "techniques/pmc/mixture_allocation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "math/tvi.h"

namespace rr::pmc {

std::vector<double> mixtureWeights(const std::vector<double>& sampleVariance,
                                   const std::vector<double>& meanLuminance, double epsilon,
                                   double cdPerUnit) {
    if (sampleVariance.size() != meanLuminance.size())
        throw std::logic_error("one variance and one luminance per pixel");
    const size_t pixels = sampleVariance.size();
    std::vector<double> alpha(pixels);
    double sum = 0;
    for (size_t k = 0; k < pixels; ++k) {
        // α'_ij = σ²_ij / tvi(L_ij), in display units.
        const double variance = sampleVariance[k] * cdPerUnit * cdPerUnit;
        alpha[k] = variance / photopicTvi(std::max(0.0, meanLuminance[k]) * cdPerUnit);
        sum += alpha[k];
    }
    const double uniform = 1.0 / double(pixels);
    for (double& a : alpha)
        a = sum > 0 ? epsilon * uniform + (1 - epsilon) * a / sum : uniform;
    return alpha;
}

void mixtureCounts(std::span<const double> alpha, uint64_t total, double u,
                   std::span<uint32_t> counts) {
    if (counts.size() != alpha.size()) throw std::logic_error("one count per weight");
    const size_t pixels = alpha.size();
    double fractionSum = 0;
    uint64_t whole = 0;
    for (size_t k = 0; k < pixels; ++k) {
        const double expected = double(total) * alpha[k];
        const double floor = std::floor(expected);
        counts[k] = static_cast<uint32_t>(floor);
        whole += counts[k];
        fractionSum += expected - floor;
    }
    const uint64_t residual = whole < total ? total - whole : 0;
    if (residual == 0 || !(fractionSum > 0)) return;
    // The fractional parts laid end to end and scaled to span exactly `residual`, the last end
    // forced to it; the points u, u + 1, … that fall in (G_{k−1}, G_k] go to pixel k. Whole
    // numbers of points: ⌈G_k − u⌉ − ⌈G_{k−1} − u⌉, so the total is exactly `residual`.
    const double scale = double(residual) / fractionSum;
    double cumulative = 0;
    int64_t before = 0;  // ⌈G_{−1} − u⌉ = ⌈−u⌉ = 0
    for (size_t k = 0; k < pixels; ++k) {
        const double expected = double(total) * alpha[k];
        cumulative += expected - std::floor(expected);
        const double end =
            k + 1 == pixels ? double(residual) : std::min(cumulative * scale, double(residual));
        const auto upTo = static_cast<int64_t>(std::ceil(end - u));
        counts[k] += static_cast<uint32_t>(upTo - before);
        before = upTo;
    }
}

std::vector<double> staticAllocation(const std::vector<double>& sampleVariance,
                                     const std::vector<double>& meanLuminance, uint64_t total,
                                     double cdPerUnit) {
    if (sampleVariance.size() != meanLuminance.size())
        throw std::logic_error("one variance and one luminance per pixel");
    const size_t pixels = sampleVariance.size();
    if (total < pixels) throw std::logic_error("a static allocation needs a sample per pixel");
    std::vector<double> a(pixels);
    double largest = 0;
    for (size_t k = 0; k < pixels; ++k) {
        const double sigma = std::sqrt(std::max(0.0, sampleVariance[k])) * cdPerUnit;
        a[k] = sigma / std::sqrt(photopicTvi(std::max(0.0, meanLuminance[k]) * cdPerUnit));
        largest = std::max(largest, a[k]);
    }
    const double n = double(total);
    std::vector<double> expected(pixels, n / double(pixels));
    if (!(largest > 0)) return expected;
    auto used = [&](double lambda) {
        double sum = 0;
        for (double ak : a)
            sum += std::max(1.0, lambda * ak);
        return sum;
    };
    // used(0) = pixels ≤ n and used(n / largest) ≥ n: the root is between; lo stays below it.
    double lo = 0, hi = n / largest;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (used(mid) < n ? lo : hi) = mid;
    }
    // What lo leaves over goes to the pixels above the floor, in proportion.
    double above = 0;
    for (size_t k = 0; k < pixels; ++k) {
        expected[k] = std::max(1.0, lo * a[k]);
        above += expected[k] - 1;
    }
    const double left = n - used(lo);
    for (double& e : expected)
        e += above > 0 ? left * (e - 1) / above : left / double(pixels);
    return expected;
}

}  // namespace rr::pmc
