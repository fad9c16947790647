// Ideal diffuse reflection, f = ρ/π (ρ a texture), sampled with a cosine-weighted hemisphere.
#pragma once

#include "scene/lobe_peaks.h"
#include "scene/texture.h"

namespace rr {

class Lambert final : public Material, public LobePeakSource {
  public:
    explicit Lambert(TexturePtr<Rgb> albedo) : albedo_(std::move(albedo)) {}
    explicit Lambert(const Rgb& albedo) : Lambert(constantTexture(albedo)) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext&, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kDiffuse; }

  private:
    TexturePtr<Rgb> albedo_;
};

}  // namespace rr
