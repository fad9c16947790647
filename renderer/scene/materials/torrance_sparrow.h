// Torrance–Sparrow microfacet reflection (Torrance & Sparrow 1967; Cook & Torrance 1982) for a
// distribution of microfacet normals:
//   f(wo, wi) = R · D(h) · G(wo, wi) · F(wo·h) / (4 cos θo cos θi),
// F the dielectric Fresnel reflectance for the index of refraction under the surface.
// `Distribution` supplies, for its parameter at a shading point (derived from the roughness
// texture): D(h), the shadowing-masking G and a half vector drawn from D·cos θh. Sampling
// reflects that half vector: pdf = D cos θh / (4 |wo·h|); half vectors that reflect wo below
// the surface are declined. Two-sided, reflection only.
#pragma once

#include "scene/lobe_peaks.h"
#include "scene/materials/microfacet.h"
#include "scene/texture.h"

namespace rr {

template <class Distribution>
class TorranceSparrow : public Material, public LobePeakSource {
  public:
    TorranceSparrow(TexturePtr<Rgb> reflectance, TexturePtr<float> roughness, float eta)
        : reflectance_(std::move(reflectance)), roughness_(std::move(roughness)), eta_(eta) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kGlossy; }

  protected:
    // The distribution's parameter at a shading point (Blinn exponent, Beckmann α).
    float parameter(const ShadingContext& ctx) const {
        return Distribution::fromRoughness(roughness_->eval(ctx));
    }

  private:
    // Both directions above the surface.
    Rgb evalUpper(const ShadingContext& ctx, float p, const Vec3& wo, const Vec3& wi) const;
    static float pdfUpper(float p, const Vec3& wo, const Vec3& wi);

    TexturePtr<Rgb> reflectance_;
    TexturePtr<float> roughness_;
    float eta_;
};

}  // namespace rr
