// Energy-normalised modified Phong reflection (Lafortune & Willems 1994, eq. 4 and §3):
//   f = kd/π + ks·(n + 2)/(2π)·cos^n α,  α the angle between wi and the mirror direction of wo,
// reciprocal, and energy-conserving when kd + ks ≤ 1 (the factory rejects constant values
// that exceed it). Sampling is a mixture: the cosine-weighted hemisphere with probability
// pd = Y(kd)/(Y(kd) + Y(ks)) (Y: Rec. 709 luminance) and the normalised cos^n α lobe around
// the mirror direction otherwise, chosen by uLobe; directions of the lobe below the surface
// are declined. pdf() is the mixture density. Peak: the mirror direction.
#pragma once

#include "scene/lobe_peaks.h"
#include "scene/texture.h"

namespace rr {

class Phong final : public Material, public LobePeakSource {
  public:
    Phong(TexturePtr<Rgb> diffuse, TexturePtr<Rgb> specular, TexturePtr<float> exponent)
        : diffuse_(std::move(diffuse)),
          specular_(std::move(specular)),
          exponent_(std::move(exponent)) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kDiffuse | kGlossy; }

  private:
    // The textures at one shading point, evaluated once per call.
    struct Parameters {
        Rgb kd, ks;
        double n;
        float diffuseProbability;  // of the cosine strategy; negative when both parts are black
    };
    Parameters at(const ShadingContext& ctx) const;
    static Rgb evalWith(const Parameters& p, const Vec3& wo, const Vec3& wi);
    static float pdfWith(const Parameters& p, const Vec3& wo, const Vec3& wi);

    TexturePtr<Rgb> diffuse_, specular_;
    TexturePtr<float> exponent_;
};

}  // namespace rr
