// Ideal diffuse reflection, f = ρ/π, sampled with a cosine-weighted hemisphere.
#pragma once

#include "scene/material.h"

namespace rr {

class Lambert final : public Material {
  public:
    explicit Lambert(const Rgb& albedo) : albedo_(albedo) {}

    Rgb eval(const ShadingContext&, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext&, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext&, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kDiffuse; }

  private:
    Rgb albedo_;
};

}  // namespace rr
