// Piecewise-constant discrete distribution over n items, sampled by CDF inversion in O(1)
// expected time: a guide table (Chen & Asau 1974) gives, for each of n equal slices of [0, 1),
// the index where the search for u in that slice starts, so a draw reads a cache line or two
// instead of a binary search's log n; each item's CDF value, probability and guide entry share
// one 16-byte record for the same reason (an environment map samples a row of a million-texel
// table per light sample, and resampling draws many light samples). The result is the binary
// search's exactly. Used for light selection by power and for tabulated importance.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace rr {

class Distribution1D {
  public:
    Distribution1D() = default;
    // Weights must be finite and non-negative; all-zero weights become uniform.
    explicit Distribution1D(std::span<const float> weights);

    // Returns an index with probability weight/sum, and the remapped u in [0,1) for reuse.
    int sample(float u, float* pmf = nullptr, float* uRemapped = nullptr) const;
    float pmf(int index) const { return entries_[size_t(index)].pmf; }
    // The inverse of sample(): the u that selects `index` with remapped value `uRemapped`
    // (TAIS's preimage-space maps index decisions by the uniform coordinates behind them).
    float invert(int index, float uRemapped) const;
    int size() const { return entries_.empty() ? 0 : static_cast<int>(entries_.size() - 1); }

  private:
    struct Entry {
        double cdf;      // P(index < i); entry n holds 1
        float pmf;       // P(index = i)
        uint32_t guide;  // the last j with cdf_j ≤ i/n: where the search for u ≥ i/n starts
    };
    std::vector<Entry> entries_;  // n + 1
};

}  // namespace rr
