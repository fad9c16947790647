// Piecewise-constant discrete distribution over n items with O(log n) sampling by CDF
// inversion. Used for light selection by power, and later for tabulated importance.
#pragma once

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
    float pmf(int index) const { return pmf_[index]; }
    // The inverse of sample(): the u that selects `index` with remapped value `uRemapped`
    // (TAIS's preimage-space maps index decisions by the uniform coordinates behind them).
    float invert(int index, float uRemapped) const;
    int size() const { return static_cast<int>(pmf_.size()); }

  private:
    std::vector<float> pmf_;
    std::vector<double> cdf_;  // cdf_[i] = P(index < i); size n + 1, cdf_[n] = 1
};

}  // namespace rr
