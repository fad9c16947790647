// Linear blend of two materials, f = w·fA + (1 − w)·fB with a weight texture w ∈ [0, 1]
// (e.g. "diffuse + glossy"). Sampling picks A when uLobe < w and passes the child a uLobe
// rescaled to [0, 1), so each child sees a uniform lobe number as if it were alone; the pdf
// is the mixture w·pA + (1 − w)·pB, and the weight f/pdf is that of the combination (for a
// specular child's sample, whose probability is scaled by w, the child's own weight).
// The children belong to the scene (SceneBuilder::addMaterial).
#pragma once

#include "scene/lobe_peaks.h"
#include "scene/texture.h"

namespace rr {

class MixMaterial final : public Material, public LobePeakSource {
  public:
    MixMaterial(const Material* a, const Material* b, TexturePtr<float> weight)
        : a_(a),
          b_(b),
          peaksA_(lobePeakSource(*a)),
          peaksB_(lobePeakSource(*b)),
          weight_(std::move(weight)) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override;
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    // Both children's peaks, when both know theirs.
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override;
    bool findsPeaks() const override { return peaksA_ && peaksB_; }
    uint8_t lobes() const override { return a_->lobes() | b_->lobes(); }

  private:
    const Material* a_;
    const Material* b_;
    const LobePeakSource* peaksA_;  // nullptr: the child does not know its peaks
    const LobePeakSource* peaksB_;
    TexturePtr<float> weight_;
};

}  // namespace rr
