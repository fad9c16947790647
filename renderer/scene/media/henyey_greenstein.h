// The Henyey–Greenstein phase function (Henyey & Greenstein 1941):
//   p(cos θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}),
// with θ the scattering angle as in phase_function.h (cos θ = −dot(wo, wi)), so g > 0 scatters
// forward, g < 0 backward, g = 0 is isotropic; g is the mean cosine E[cos θ]. Sampled exactly
// by inverting the CDF of cos θ; g ∈ (−1, 1).
#pragma once

#include "scene/phase_function.h"

namespace rr {

class HenyeyGreenstein final : public PhaseFunction {
  public:
    explicit HenyeyGreenstein(float g) : g_(g) {}

    float eval(const Vec3& wo, const Vec3& wi) const override;
    float pdf(const Vec3& wo, const Vec3& wi) const override;
    float sample(const Vec3& wo, Vec2 u, Vec3* wi) const override;

    float g() const { return g_; }

  private:
    // p as a function of cos θ.
    float density(float cosTheta) const;
    // The inverse CDF of cos θ at ξ ∈ [0, 1).
    float sampleCosTheta(float xi) const;

    float g_;
};

}  // namespace rr
