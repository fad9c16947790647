// Two materials in a checkerboard of the texture coordinates (scene/checkerboard.h): every
// query is passed to the material of the square ctx.uv falls in, e.g. PMC fig. 6's floor of
// diffuse and glossy squares. The two materials belong to the scene.
#pragma once

#include "scene/checkerboard.h"
#include "scene/lobe_peaks.h"

namespace rr {

class CheckerMaterial final : public Material, public LobePeakSource {
  public:
    CheckerMaterial(const Material* even, const Material* odd, Checkerboard board)
        : even_(even),
          odd_(odd),
          evenPeaks_(lobePeakSource(*even)),
          oddPeaks_(lobePeakSource(*odd)),
          board_(board) {}

    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override {
        return at(ctx).eval(ctx, wo, wi);
    }
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override {
        return at(ctx).pdf(ctx, wo, wi);
    }
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override {
        return at(ctx).sample(ctx, wo, uLobe, uDirection, out);
    }
    void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const override {
        (board_.isEven(ctx.uv) ? evenPeaks_ : oddPeaks_)->peaks(ctx, wo, out);
    }
    bool findsPeaks() const override { return evenPeaks_ && oddPeaks_; }
    uint8_t lobes() const override { return even_->lobes() | odd_->lobes(); }

  private:
    const Material& at(const ShadingContext& ctx) const {
        return board_.isEven(ctx.uv) ? *even_ : *odd_;
    }

    const Material* even_;
    const Material* odd_;
    const LobePeakSource* evenPeaks_;  // nullptr: the material does not know its peaks
    const LobePeakSource* oddPeaks_;
    Checkerboard board_;
};

}  // namespace rr
