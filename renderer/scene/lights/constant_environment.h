// An environment of constant radiance L in every direction (the "uniform lighting" of the RIS
// paper's fig. 5, and the closed-form test case: a diffuse convex object under it reflects
// albedo·L). Sampled uniformly over the sphere (`luminance` is the same for a constant map), or
// cosine-weighted about the receiver's normal (env_sampling.h).
#pragma once

#include "scene/invertible_light.h"
#include "scene/light.h"
#include "scene/lights/env_sampling.h"

namespace rr {

class ConstantEnvironment final : public Light, public InvertibleLight {
  public:
    explicit ConstantEnvironment(const Rgb& radiance, EnvSampling sampling = EnvSampling::Uniform)
        : radiance_(radiance),
          sampling_(sampling == EnvSampling::Cosine ? sampling : EnvSampling::Uniform) {}

    bool sample(const LightReference& reference, Vec2 u, float time,
                LightSample* out) const override;
    float pdf(const Vec3&, const SurfaceHit&) const override { return 0; }
    // Flux through the scene's bounding sphere: π r² (its cross-section) · 4π · L.
    Rgb power() const override { return radiance_ * (4.0f * kPi * kPi * radius_ * radius_); }
    bool isDelta() const override { return false; }
    bool isInfinite() const override { return true; }
    Rgb escapedRadiance(const Vec3&) const override { return radiance_; }
    float directionPdf(const LightReference& reference, const Vec3& w) const override;
    // The inverse of the direction sampling at `direction`.
    bool invertSample(const LightReference& reference, const Vec3& direction, const Vec3& point,
                      Vec2* u) const override;
    void preprocess(const Vec3&, float sceneRadius) override { radius_ = sceneRadius; }

  private:
    Rgb radiance_;
    EnvSampling sampling_;
    float radius_ = 1;
};

}  // namespace rr
