// Isotropic scattering: p = 1/(4π) in every direction, sampled uniformly over the sphere.
#pragma once

#include "scene/phase_function.h"

namespace rr {

class IsotropicPhase final : public PhaseFunction {
  public:
    float eval(const Vec3& wo, const Vec3& wi) const override;
    float pdf(const Vec3& wo, const Vec3& wi) const override;
    float sample(const Vec3& wo, Vec2 u, Vec3* wi) const override;
};

}  // namespace rr
