// Cook–Torrance microfacet reflection with the Beckmann distribution of normals (Cook &
// Torrance 1982; distribution, masking and sampling as in Walter et al. 2007, §5 and §5.1):
//   f(wo, wi) = R · D(h) · G(wo, wi, h) · F(wo·h) / (4 cos θo cos θi),
//   D(h) = exp(−tan² θh / α²) / (π α² cos⁴ θh),
// with roughness = α, F the dielectric Fresnel reflectance for `ior`, and G Smith's
// shadowing-masking for the Beckmann surface, as the separable product G1(wo)·G1(wi) of the
// exact G1 (the form with erf, not its rational fit). Smith rather than Cook & Torrance's
// V-cavity: Smith's G follows from the statistics of the Beckmann microsurface itself
// (Heitz 2014), where the V-cavity profile is an assumption independent of D.
// Sampling: half vectors from D·cos θh (tan² θh = −α² ln(1 − u), Walter et al. 2007
// §5.1), reflected, pdf = D cos θh / (4 |wo·h|); half vectors that reflect wo below the
// surface are declined.
#pragma once

#include "scene/material.h"
#include "scene/texture.h"

namespace rr {

class CookTorrance final : public Material {
  public:
    // `roughness` = Beckmann α in (0, 2]; `eta` is the index of refraction under the surface.
    CookTorrance(TexturePtr<Rgb> reflectance, TexturePtr<float> roughness, float eta)
        : reflectance_(std::move(reflectance)), roughness_(std::move(roughness)), eta_(eta) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kGlossy; }

  private:
    // Both arguments above the surface.
    Rgb evalUpper(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const;

    TexturePtr<Rgb> reflectance_;
    TexturePtr<float> roughness_;
    float eta_;
};

// The Beckmann distribution D(h) for roughness α (zero below the surface).
float beckmannD(const Vec3& h, float alpha);
// Smith's masking G1(w, h) of the Beckmann surface for a direction w above it.
float beckmannSmithG1(const Vec3& w, const Vec3& h, float alpha);
// Solid-angle density of the reflected direction when half vectors follow D·cos θh.
float beckmannReflectedPdf(const Vec3& wo, const Vec3& wi, float alpha);

}  // namespace rr
