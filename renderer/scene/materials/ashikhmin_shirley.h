// Ashikhmin & Shirley's anisotropic Phong BRDF (Ashikhmin & Shirley 2000, "An Anisotropic
// Phong BRDF Model", §2–3), with n_u, n_v the exponents along the shading frame's x (u) and
// y (v) axes:
//   specular ρs = √((n_u+1)(n_v+1)) / (8π) · cos^(n_u cos² φh + n_v sin² φh) θh
//                 / ((k·h) max(cos θo, cos θi)) · F(k·h),
//   F(k·h)   = Rs + (1 − Rs)(1 − k·h)⁵   (Schlick's approximation),
//   diffuse  ρd = 28 Rd / (23π) · (1 − Rs) · (1 − (1 − cos θo/2)⁵) · (1 − (1 − cos θi/2)⁵).
// Sampling (their §3): with probability `specularProbability` a half vector from their
// anisotropic distribution p_h, reflected (pdf p_h / (4 k·h)), otherwise a cosine-weighted
// direction for the diffuse term; the pdf is the mixture of both. Exponents come from
// roughness (n = 1/roughness, pbrt-v1's "anisotropic" convention, as in the two-stage paper's
// fig. 8: roughness 0.001 and 1.0) or are given directly.
#pragma once

#include "scene/lobe_peaks.h"
#include "scene/texture.h"

namespace rr {

class AshikhminShirley final : public Material, public LobePeakSource {
  public:
    // `u` and `v` are roughnesses (n = 1/roughness) or, with `exponents`, the exponents.
    AshikhminShirley(TexturePtr<Rgb> diffuse, TexturePtr<Rgb> specular, TexturePtr<float> u,
                     TexturePtr<float> v, bool exponents)
        : diffuse_(std::move(diffuse)),
          specular_(std::move(specular)),
          u_(std::move(u)),
          v_(std::move(v)),
          exponents_(exponents) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kDiffuse | kGlossy; }

    // The material at one shading point.
    struct Parameters {
        Rgb rd, rs;
        float nu, nv;
        float specularProbability;  // of the half-vector strategy in sample()
    };
    Parameters at(const ShadingContext& ctx) const;

  private:
    TexturePtr<Rgb> diffuse_, specular_;
    TexturePtr<float> u_, v_;
    bool exponents_;
};

}  // namespace rr
