// Torrance–Sparrow microfacet reflection with the Blinn–Phong distribution of normals
// (Blinn 1977; Cook & Torrance 1982):
//   f(wo, wi) = R · D(h) · G(wo, wi) · F(wo·h) / (4 cos θo cos θi),
//   D(h) = (e + 2)/(2π) · cos^e θh,
// normalised so that ∫ D cos θh dω = 1; G is the V-cavity shadowing-masking term and F the
// dielectric Fresnel reflectance for `ior`. The exponent is e = 1/roughness, pbrt-v1's
// convention, which the two-stage paper used ("Blinn, roughness 0.02" is e = 50).
// Sampling: half vectors from D·cos θh, reflected, pdf = D cos θh / (4 |wo·h|); half vectors
// that reflect wo below the surface are declined.
#pragma once

#include "scene/material.h"
#include "scene/texture.h"

namespace rr {

class Blinn final : public Material {
  public:
    // `roughness` in (0, 1]; `eta` is the index of refraction under the surface.
    Blinn(TexturePtr<Rgb> reflectance, TexturePtr<float> roughness, float eta)
        : reflectance_(std::move(reflectance)), roughness_(std::move(roughness)), eta_(eta) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kGlossy; }

    // The Blinn–Phong exponent at a shading point: e = 1/roughness.
    float exponent(const ShadingContext& ctx) const { return 1.0f / roughness_->eval(ctx); }

  private:
    // Both arguments above the surface.
    Rgb evalUpper(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const;
    float pdfUpper(float exponent, const Vec3& wo, const Vec3& wi) const;

    TexturePtr<Rgb> reflectance_;
    TexturePtr<float> roughness_;
    float eta_;
};

// The Blinn–Phong normal distribution D(h) = (e + 2)/(2π) cos^e θh.
float blinnD(const Vec3& h, float exponent);

}  // namespace rr
