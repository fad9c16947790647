// A homogeneous medium: constant absorption σa and scattering σs (RGB, per unit length),
// extinction σt = σa + σs, transmittance Tr(d) = e^{−σt d} per channel, and a phase function.
//
// Free-flight distances for RGB σt: a single density must serve all three channels and stay
// positive wherever any channel's integrand is, or the estimator is biased for chromatic
// media. We use the equal-weight mixture of the channels' exponentials (the density of Veach's
// one-sample model over the three channels' strategies with the balance heuristic, Veach 1997
// §9.2.4):
//   S(t) = mean_c e^{−σt,c t}  (probability of no collision before t),
//   pdf(t) = −S'(t) = mean_c σt,c e^{−σt,c t},
// drawn by inverting S rather than by first picking a channel, so that u → t is one monotone
// map (see medium.h). For grey σt this is t = −ln(v)/σt; otherwise ln S is convex and
// decreasing and Newton's method from t0 = −ln(v)/max σt, which lies left of the root,
// converges monotonically. A channel with σt = 0 contributes no density and survival 1, so
// the flight then escapes to infinity with probability (number of such channels)/3.
#pragma once

#include <memory>

#include "scene/medium.h"

namespace rr {

class HomogeneousMedium final : public Medium {
  public:
    HomogeneousMedium(const Rgb& sigmaA, const Rgb& sigmaS, std::unique_ptr<PhaseFunction> phase);

    Rgb transmittance(float distance) const override;
    float survival(float distance) const override;
    FreeFlight sampleFreeFlight(float budget, float tMax) const override;
    const PhaseFunction& phase() const override { return *phase_; }

    // The distance map of the MediumDistance decision, t = S⁻¹(v) for v = 1 − u, defined for
    // S(∞) < v ≤ 1, and its density pdf(t): a preimage-space warp of u multiplies this pdf by
    // the warp's density.
    float distanceForSurvival(float v) const;
    float distancePdf(float t) const;

    const Rgb& sigmaT() const { return sigmaT_; }
    const Rgb& sigmaS() const { return sigmaS_; }

  private:
    Rgb sigmaS_, sigmaT_;
    bool grey_;  // σt equal in all channels: closed-form inversion
    std::unique_ptr<PhaseFunction> phase_;
};

}  // namespace rr
