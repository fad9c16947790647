#include "techniques/pmc/mixture_allocation.h"

#include <cmath>
#include <stdexcept>

#include "metrics/tvi.h"

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

void mixtureCounts(const std::vector<double>& alpha, uint64_t total, double u,
                   std::vector<uint32_t>* counts) {
    const size_t pixels = alpha.size();
    counts->assign(pixels, 0);
    double fractionSum = 0;
    uint64_t whole = 0;
    for (size_t k = 0; k < pixels; ++k) {
        const double expected = double(total) * alpha[k];
        const double floor = std::floor(expected);
        (*counts)[k] = static_cast<uint32_t>(floor);
        whole += (*counts)[k];
        fractionSum += expected - floor;
    }
    const uint64_t residual = whole < total ? total - whole : 0;
    if (residual == 0 || !(fractionSum > 0)) return;
    // Points u, u + 1, …, u + residual − 1 on the fractional parts laid end to end, scaled so
    // that they span exactly `residual` (Σ frac equals it up to rounding).
    const double scale = fractionSum / double(residual);
    double next = u * scale, end = 0;
    for (size_t k = 0; k < pixels; ++k) {
        const double expected = double(total) * alpha[k];
        end += expected - std::floor(expected);
        if (next < end) {  // a fraction < 1 holds at most one point (up to rounding)
            ++(*counts)[k];
            next += scale;
        }
    }
}

}  // namespace rr::pmc
