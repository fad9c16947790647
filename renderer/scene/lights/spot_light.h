// Spot light: a point light whose radiant intensity I(θ) = I₀ · falloff(cos θ) depends on the
// angle θ from its axis. Full intensity inside the falloff-start cone, zero outside the cone,
// and between them smoothstep in cos θ: falloff = x²(3 − 2x), x = (cos θ − cos θc)/(cos θs −
// cos θc). Smoothstep is C¹ at both ends (no Mach band at either edge of the penumbra, unlike a
// linear ramp), is the falloff pbrt-v4 uses (so scenes port with the same look), and its
// integral over x is ½, which gives the power in closed form (see power()).
#pragma once

#include "scene/light.h"

namespace rr {

class SpotLight final : public Light {
  public:
    // `axis` unit; angles in radians with 0 ≤ falloffStart ≤ cone ≤ π/2, cone > 0.
    SpotLight(const Vec3& position, const Vec3& axis, const Rgb& intensity, float cone,
              float falloffStart);

    bool sample(const LightReference& reference, Vec2 u, float time,
                LightSample* out) const override;
    float pdf(const Vec3&, const SurfaceHit&) const override { return 0; }
    // Φ = ∫ I dω = 2π I₀ ∫ falloff(μ) dμ over μ = cos θ ∈ [cos θc, 1]
    //   = 2π I₀ [(1 − cos θs) + ½ (cos θs − cos θc)] = π I₀ (2 − cos θs − cos θc).
    Rgb power() const override { return power_; }
    bool isDelta() const override { return true; }

    // I(direction)/I₀ for a unit direction leaving the light.
    float falloff(const Vec3& direction) const;

  private:
    Vec3 position_, axis_;
    Rgb intensity_;
    float oneMinusCosCone_, oneMinusCosFalloffStart_;
    Rgb power_;
};

}  // namespace rr
