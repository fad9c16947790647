// PMC-IP's image-plane kernel (Lai et al. 2007 §4): a mixture over pixels,
// K(x) = Σ α_ij h_ij(x), h_ij uniform over pixel (i, j). Two steps per iteration, each a pure
// function of the image so far so that they can be tested alone:
//  - the adaptation (§4.2), α from each pixel's sample variance against the threshold of
//    visibility at its brightness;
//  - deterministic mixture sampling (§4.3), α into whole sample counts.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace rr::pmc {

// §4.2, read as α_ij = ε/|P| + (1 − ε) α'_ij / Σ α' with α'_ij = σ²_ij / tvi(L_ij) (the printed
// α = ε + (1 − ε)α'/Σα' does not sum to one; README.md, reading 1). σ² is the per-sample
// variance of the pixel's luminance and L its mean luminance, both taken to cd/m² by
// `cdPerUnit`, the metrics tool's display scale, so the adaptation minimises the error the
// tables report. When every α' is zero (a flat image), α is uniform.
std::vector<double> mixtureWeights(const std::vector<double>& sampleVariance,
                                   const std::vector<double>& meanLuminance, double epsilon,
                                   double cdPerUnit);

// §4.3: pixel k gets ⌊N α_k⌋ samples, and the N − Σ⌊N α⌋ left over go to pixels with
// probability proportional to their fractional parts, by systematic sampling (one offset
// `u` ∈ [0, 1), stride 1 over the fractional parts laid end to end), so each pixel gets
// ⌊N α_k⌋ or ⌈N α_k⌉ samples (up to rounding), N in all, and E[n_k] = N α_k (the paper does not say
// which residual scheme; README.md, "Residual draw"). PMC-HI counts its components' samples the
// same way (§5). `counts` has one entry per weight.
void mixtureCounts(std::span<const double> alpha, uint64_t total, double u,
                   std::span<uint32_t> counts);

// The best static allocation of `total` samples for the tvi error when each pixel's per-sample
// variance σ² is known (the bound of Table 1's rows, not the paper's rule): the error of a
// pixel estimated from n independent samples is σ²/(n tvi(L)), and Σ σ²/(n tvi) over the image
// with Σ n = total and every n ≥ 1 is least at n = max(1, λ σ/√tvi) (Lagrange, with the
// bound's multiplier: water-filling), λ found by bisection. Returns the expected counts n (at
// least 1 each, summing to `total`). A flat image gets total / pixels each.
std::vector<double> staticAllocation(const std::vector<double>& sampleVariance,
                                     const std::vector<double>& meanLuminance, uint64_t total,
                                     double cdPerUnit);

}  // namespace rr::pmc
