// How many candidates per sample (M) and samples per shading point (N) resampled importance
// sampling spends (Talbot et al. 2005 §4.2–4.3): the variance terms of eq. (2), the optimal M of
// eq. (3), the robust M of eq. (4), and the procedure that fits M and N into a time budget.
#pragma once

#include <cstdint>

#include "math/rgb.h"

namespace rr::ris {

// M and N of eq. (1); fractional values are rounded randomly per shading point.
struct CandidateCounts {
    double m = 1, n = 1;
};

// Seconds to draw one candidate and evaluate its resampling weight (T_X), and to finish a
// chosen sample, mostly its shadow ray (T_Y).
struct CandidateCosts {
    double tX = 0, tY = 0;
};

// The terms of eq. (2), per colour channel, estimated from samples X ~ p of the integrand f
// (RGB), the target ĝ and the source density p:
//   e1 = E[f/p]², e2 = E[f²/(ĝ p)] · E[ĝ/p], e3 = E[f²/p²],
// so that V[RIS] = (1/N)((e3 − e2)/M + (e2 − e1)) and V[IS] = (1/N)(e3 − e1). A sample with
// ĝ = 0 has f = 0 (ĝ drops only visibility) and adds 0 to E[f²/(ĝ p)].
class VarianceTerms {
  public:
    void add(const Rgb& f, float target, float pdf);
    uint32_t count() const { return count_; }
    Rgb e1() const;
    Rgb e2() const;
    Rgb e3() const;
    // |e3 − e2| and |e2 − e1| in the l2 norm over the channels (the paper's length function).
    double sourceExcess() const;
    double targetExcess() const;

  private:
    struct Terms {
        double e1[3], e2[3], e3[3];
    };
    Terms terms() const;  // per channel, in double precision

    uint32_t count_ = 0;
    double fOverP[3] = {0, 0, 0};
    double fSquaredOverGP[3] = {0, 0, 0};
    double fSquaredOverPSquared[3] = {0, 0, 0};
    double gOverP = 0;
};

// Eq. (4): M_r = T_Y / T_X (equal time for both stages).
double robustCandidates(const CandidateCosts& costs);
// Eq. (3): M* = √(|e3 − e2| / |e2 − e1| · T_Y / T_X); `maxCandidates` when |e2 − e1| = 0 (the
// target is proportional to f: only M reduces the variance), 1 when |e3 − e2| = 0.
double optimalCandidates(const VarianceTerms& terms, const CandidateCosts& costs,
                         double maxCandidates);

// §4.2's procedure for a wanted M within the time T = budget · (T_X + T_Y) of `budget` plain
// light samples (M = 1): clamp M to [1, maxCandidates], N = T / (M T_X + T_Y) clamped ≥ 1, then
// M = (T/N − T_Y) / T_X again (within the same bounds).
CandidateCounts countsWithinBudget(double wantedCandidates, const CandidateCosts& costs,
                                   double budget, double maxCandidates);

}  // namespace rr::ris
