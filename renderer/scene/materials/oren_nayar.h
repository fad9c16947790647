// Rough diffuse reflection: the qualitative model of Oren & Nayar 1994 (§4.4, eq. 30), V-groove
// microfacets with Lambertian facets whose slopes have standard deviation σ:
//   f = ρ/π·(A + B·max(0, cos(φi − φo))·sin α·tan β),  α = max(θi, θo), β = min(θi, θo),
//   A = 1 − 0.5·σ²/(σ² + 0.33),  B = 0.45·σ²/(σ² + 0.09).
// σ = 0 is Lambert. Sampled with the cosine-weighted hemisphere. Peaks (two-stage §4): the
// retro-reflection direction (= wo), which the model was designed for, and the normal.
#pragma once

#include "scene/lobe_peaks.h"
#include "scene/texture.h"

namespace rr {

class OrenNayar final : public Material, public LobePeakSource {
  public:
    // `sigmaDegrees`: the facet slope deviation σ in degrees.
    OrenNayar(TexturePtr<Rgb> albedo, TexturePtr<float> sigmaDegrees)
        : albedo_(std::move(albedo)), sigmaDegrees_(std::move(sigmaDegrees)) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kDiffuse; }

  private:
    TexturePtr<Rgb> albedo_;
    TexturePtr<float> sigmaDegrees_;
};

}  // namespace rr
