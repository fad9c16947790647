// Diffuse emitter attached to a shape: constant radiance on the normal's side (or both sides).
#pragma once

#include "scene/invertible_light.h"
#include "scene/light.h"
#include "scene/shape.h"

namespace rr {

class AreaLight final : public Light, public InvertibleLight {
  public:
    AreaLight(const Shape* shape, const Rgb& radiance, bool twoSided)
        : shape_(shape), radiance_(radiance), twoSided_(twoSided) {}

    bool sample(const LightReference& reference, Vec2 u, float time,
                LightSample* out) const override;
    float pdf(const Vec3& reference, const SurfaceHit& hit) const override;
    // The shape's inverse (Shape::invertSampleDirection); `direction` is not needed: a point of
    // the shape determines u. Given for any point of the shape, also one that does not emit
    // towards the reference (one-sided lights seen from behind), for which sample() refuses u.
    bool invertSample(const LightReference& reference, const Vec3& direction, const Vec3& point,
                      Vec2* u) const override;
    bool invertsSamples() const override { return shape_->invertsSamples(); }
    Rgb power() const override;
    bool isDelta() const override { return false; }

    // Radiance leaving the surface at a point with normal `normal` towards direction `w`.
    Rgb emitted(const Vec3& normal, const Vec3& w) const {
        return (twoSided_ || dot(normal, w) > 0) ? radiance_ : Rgb(0.0f);
    }

  private:
    const Shape* shape_;
    Rgb radiance_;
    bool twoSided_;
};

}  // namespace rr
