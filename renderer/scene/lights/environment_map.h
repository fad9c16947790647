// An environment map: radiance arriving from every direction, read from an image laid out by an
// EnvLayout (latitude-longitude or angular probe) and rotated into the world.
//
// The map is piecewise constant: a direction sees the texel it falls in (nearest lookup, no
// filtering). That is exactly what the sampling density assumes, so radiance/pdf stays bounded
// within a texel, and texels masked out (the probe's outside, with its copyright notice) cannot
// bleed into their neighbours as they would under bilinear filtering.
//
// Importance sampling: a texel is chosen with probability ∝ luminance × its solid angle (the
// mean of dω/(ds dt) over it; TexelSampler), a point uniformly inside it, and the direction
// there; the solid-angle density is p(s, t) / (dω/(ds dt)) (the change of variables from image
// to sphere). A sample carries the radiance and density of the texel it was drawn in, read from
// the sampler's guide slot with the draw, not looked up again from its direction: escaped rays
// and MIS find the same texel and density for that direction except where float rounding moves
// the direction across a texel edge (a few in 10⁵ draws, measured in the tests), as pbrt-v4's
// image light does.
//
// `sampling` other than `luminance` (env_sampling.h) ignores the map when drawing directions:
// cosine-weighted about the receiver's normal or uniform, as pbrt-v1's plain `infinite` light,
// for baselines configured like the papers' renderers. The stand-in is then sample() itself.
//
// Resampling's stand-in (sampleStandIn): the same map coarsened to blocks of texels, so that a
// candidate reads two small tables that stay in cache instead of the texel tables (since those
// were laid out for the cache, issue 40, the stand-in saves little: ĝ is then exact). A block is chosen with probability ∝ its texels' weights, a point uniformly in it;
// its radiance is the block's solid-angle-weighted mean. Any block holding a texel of non-zero
// weight has non-zero probability and radiance, so RIS stays unbiased with it.
#pragma once

#include <memory>
#include <vector>

#include "io/rgb_image_io.h"
#include "math/frame.h"
#include "sampling/distribution2d.h"
#include "sampling/texel_sampler.h"
#include "scene/invertible_light.h"
#include "scene/light.h"
#include "scene/light_stand_in.h"
#include "scene/lights/env_layout.h"
#include "scene/lights/env_sampling.h"

namespace rr {

class EnvironmentMap final : public Light, public LightStandIn, public InvertibleLight {
  public:
    // `image` must hold finite values (negative ones are clamped to 0: lossy EXR compression
    // leaves some). Its radiance is multiplied by `scale`; `toWorld` is a rotation (its axes
    // are the images of the map's X, Y, Z).
    EnvironmentMap(RgbImage image, std::unique_ptr<EnvLayout> layout, const Rgb& scale,
                   const Frame& toWorld, EnvSampling sampling = EnvSampling::Luminance);

    bool sample(const LightReference& reference, Vec2 u, float time,
                LightSample* out) const override;
    // Locates every draw in the texel tables before reading any texel record.
    void sampleMany(const LightReference& reference, std::span<const Vec2> u, float time,
                    LightSample* out, bool* drawn) const override;
    bool sampleStandIn(const LightReference& reference, Vec2 u, float time,
                       LightSample* out) const override;
    Rgb exactRadiance(const LightSample& s) const override { return escapedRadiance(s.direction); }
    float pdf(const Vec3&, const SurfaceHit&) const override { return 0; }
    // Flux through the scene's bounding sphere: π r² ∫ L dω (its cross-section times the
    // radiance integrated over directions, as for ConstantEnvironment).
    Rgb power() const override { return radianceIntegral_ * (kPi * radius_ * radius_); }
    bool isDelta() const override { return false; }
    bool isInfinite() const override { return true; }
    Rgb escapedRadiance(const Vec3& w) const override;
    float directionPdf(const LightReference& reference, const Vec3& w) const override;
    // sample() backwards: the direction into the map's frame, its image point (the layout's
    // imagePoint), and the u that TexelSampler::sample maps there (TexelSampler::invert).
    // False where the density is zero, as no u yields the direction there: the lat-long poles
    // and the probe's rim (no solid angle), texels of zero weight (black ones, the probe's
    // masked ones). Other `sampling`: invertEnvDirection.
    bool invertSample(const LightReference& reference, const Vec3& direction, const Vec3& point,
                      Vec2* u) const override;
    void preprocess(const Vec3&, float sceneRadius) override { radius_ = sceneRadius; }

    const EnvLayout& layout() const { return *layout_; }
    // The map's frame in the world (its axes are the images of the map's X, Y, Z).
    const Frame& toWorld() const { return toWorld_; }
    int width() const { return image_.width; }
    int height() const { return image_.height; }
    // The radiance of texel (col, row), as escaped rays see it (scaled and masked).
    const Rgb& texel(int col, int row) const {
        return image_.pixels[size_t(row) * image_.width + col];
    }
    // Fills `out`'s direction (world, unit), shadow-ray target and flags for a direction drawn
    // by a sampler of the caller's; radiance and pdf are the caller's.
    void aim(const Vec3& reference, const Vec3& direction, LightSample* out) const;
    // ∫ L dω over the sphere: Σ texel radiance × texel solid angle.
    const Rgb& radianceIntegral() const { return radianceIntegral_; }
    // The side of sampleStandIn()'s blocks, in texels (1: the stand-in is sample() itself).
    int proxyBlock() const { return proxy_.block; }

  private:
    // sampleStandIn()'s coarsened map: block × block texels per cell.
    struct Proxy {
        int block = 1;
        Distribution2D distribution;
        std::vector<Rgb> radiance;  // per cell: Σ L·dω / Σ dω over its texels
    };

    int texelIndex(Vec2 st) const;
    // sample()'s end with `luminance` sampling, from the texel the tables found.
    bool sampleFromTexel(const LightReference& reference, const TexelSampler::Ticket& ticket,
                         LightSample* out) const;
    // The sampling density per unit image area at `st` (0 without the map's tables).
    float imageDensity(Vec2 st) const;
    // A sample's direction (from the map's frame) and the shadow-ray target far along it.
    void setDirection(const Vec3& reference, const Vec3& local, LightSample* out) const;
    void buildProxy(const std::vector<float>& weights, const std::vector<float>& jacobians);

    RgbImage image_;  // scaled and masked
    std::unique_ptr<EnvLayout> layout_;
    Frame toWorld_;
    TexelSampler texels_;  // `luminance` sampling only
    Rgb radianceIntegral_;
    Proxy proxy_;
    EnvSampling sampling_;
    float radius_ = 1;
};

}  // namespace rr
