// Generalised cosine lobes (Lafortune, Foo, Torrance & Greenberg 1997, eq. 5 and §4) plus a
// diffuse term:
//   f = ρd/π + Σ_i ρ_i·max(0, Cx,i·ux·vx + Cy,i·uy·vy + Cz,i·uz·vz)^(n_i).
// For an outgoing u the lobe is |a|^n·cos^n α around the axis a = (Cx ux, Cy uy, Cz uz), α the
// angle between v and a: Cx = Cy = −Cz gives a Phong lobe around the mirror direction,
// Cx = Cy > 0 retro-reflection, Cx = Cy = 0 a lobe around the normal. The model is reciprocal.
// Sampling chooses the diffuse part or one lobe with uLobe, with probabilities proportional to
// their contributions to the directional albedo (luminance), and samples the chosen lobe's
// normalised cos^n α around its axis (scene/materials/cosine_lobe.h); pdf() is the mixture.
// Peaks (two-stage §4): the lobe axes above the surface.
#pragma once

#include <vector>

#include "scene/lobe_peaks.h"
#include "scene/texture.h"

namespace rr {

struct LafortuneLobe {
    Vec3 c;          // (Cx, Cy, Cz)
    float exponent;  // n ≥ 0
    Rgb albedo;      // ρ: scales the lobe; not normalised (see Lafortune::lobeAlbedo)
};

class Lafortune final : public Material, public LobePeakSource {
  public:
    static constexpr int kMaxLobes = 16;

    // At most kMaxLobes lobes (std::invalid_argument otherwise).
    Lafortune(TexturePtr<Rgb> diffuse, const std::vector<LafortuneLobe>& lobes);

    // The fit of the model to measured human skin that pbrt-v1 ships as its "skin" material
    // (materials/skin.cpp; Pharr & Humphreys 2004) and the two-stage paper renders in fig. 8:
    // three lobes whose Cx = Cy, Cz and n differ per colour channel, so each is given here as
    // three lobes with albedo 1 in one channel.
    static Rgb skinDiffuse();
    static std::vector<LafortuneLobe> skinLobes();

    // Directional albedo of the lobes (without the diffuse part) for `wo`, per channel, from
    // a table of each lobe's integral against the clamped cosine.
    Rgb lobeAlbedo(const Vec3& wo) const;
    // The largest lobeAlbedo over outgoing directions (a 1° grid in θ and 10° in φ), and the
    // direction where it is reached. Together with the diffuse albedo it must not exceed 1.
    Rgb maxLobeAlbedo(Vec3* where) const;

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kDiffuse | kGlossy; }

  private:
    struct Lobe {
        LafortuneLobe params;
        // ∫ cos^n α·max(0, cos θ) dω over the lobe, tabulated against the axis' cos θ.
        std::vector<float> clippedIntegral;
    };
    // A lobe as seen from one outgoing direction.
    struct Oriented {
        Vec3 axis;     // unit; the peak direction
        double scale;  // |a|^n
    };
    // Everything that depends on the shading point and wo only, computed once per query.
    struct View {
        Rgb diffuse;
        Oriented lobe[kMaxLobes];
        double weight[kMaxLobes];  // sampling weights: the lobes' albedos (luminance)
        double diffuseWeight, total;
    };
    static Oriented orient(const Lobe& lobe, const Vec3& wo);
    static double clippedIntegral(const Lobe& lobe, double axisCos);
    View view(const ShadingContext& ctx, const Vec3& wo) const;
    // f·|cos θi| and the pdf of wi (on wo's side), from one evaluation of each lobe's cos^n α.
    void evaluate(const View& v, const Vec3& wi, Rgb* f, float* pdf) const;

    TexturePtr<Rgb> diffuse_;
    std::vector<Lobe> lobes_;
};

}  // namespace rr
