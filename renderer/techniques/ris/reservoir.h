// Importance resampling without storing the candidates (Talbot et al. 2005 §3): a streaming
// weighted reservoir keeps candidate j of a stream with probability w_j / Σ_{k≤j} w_k, which
// leaves it holding candidate j with probability w_j / Σw once the stream ends; the estimator
// of eq. (1) needs only the kept candidate and Σw.
#pragma once

#include <cmath>
#include <cstdint>

namespace rr::ris {

template <class Candidate>
class WeightedReservoir {
  public:
    // Offers a candidate of resampling weight w ≥ 0 (ĝ/p); `u` uniform in [0, 1), independent
    // of the candidates, decides whether it replaces the one held.
    void offer(const Candidate& candidate, float w, float u) {
        ++offered_;
        if (!(w > 0)) return;
        // The first candidate of positive weight is kept whatever u is: for a denormal weight
        // (a light that barely reaches the point) u·w rounds to w in float, and the reservoir
        // would be non-empty holding no candidate.
        const bool first = !(weightSum_ > 0);
        weightSum_ += w;
        if (first || u * weightSum_ < w) kept_ = candidate;
    }

    bool empty() const { return !(weightSum_ > 0); }
    const Candidate& kept() const { return kept_; }
    float weightSum() const { return weightSum_; }
    uint32_t offered() const { return offered_; }

  private:
    Candidate kept_{};
    float weightSum_ = 0;
    uint32_t offered_ = 0;
};

// One sample of eq. (1): offers `m` candidates to a reservoir, candidate j from draw(j, &c)
// (false: none drawn, which still counts in M) with the resampling weight c.target / c.pdf
// (ĝ/p) and the uniform select(j); keeps one, Y, in *kept, and gives its density as eq. (1)
// divides by it: ĝ(Y) / ((1/M) Σw), or with M = 1 p(Y) itself (plain importance sampling: no
// selection is drawn, and the arithmetic is the same). False when every weight was 0.
template <class Candidate, class Draw, class Select>
bool resample(uint32_t m, const Draw& draw, const Select& select, Candidate* kept, float* density) {
    WeightedReservoir<Candidate> reservoir;
    for (uint32_t j = 0; j < m; ++j) {
        Candidate c;
        if (!draw(j, &c)) continue;
        reservoir.offer(c, c.target / c.pdf, m == 1 ? 0.0f : select(j));
    }
    if (reservoir.empty()) return false;
    *kept = reservoir.kept();
    *density = m == 1 ? kept->pdf : kept->target * static_cast<float>(m) / reservoir.weightSum();
    return true;
}

// ⌊x⌋ or ⌈x⌉ with the probabilities that keep the expectation x (Talbot et al. 2005 §4.2:
// "we probabilistically take the floor or the ceiling of M and N"); u uniform in [0, 1).
inline uint32_t roundRandomly(double x, float u) {
    const double floor = std::floor(x);
    return static_cast<uint32_t>(floor) + (u < x - floor ? 1u : 0u);
}

}  // namespace rr::ris
