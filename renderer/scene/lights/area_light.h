// Diffuse emitter attached to a shape: constant radiance on the normal's side (or both sides).
#pragma once

#include "scene/invertible_light.h"
#include "scene/light.h"
#include "scene/light_stand_in.h"
#include "scene/shape.h"

namespace rr {

class AreaLight final : public Light, public InvertibleLight, public LightStandIn {
  public:
    AreaLight(const Shape* shape, const Rgb& radiance, bool twoSided)
        : shape_(shape), radiance_(radiance), twoSided_(twoSided) {}

    bool sample(const LightReference& reference, Vec2 u, float time,
                LightSample* out) const override;
    // The stand-in, on shapes whose own sampling is expensive: uniform by area, its density
    // converted to solid angle (a worse density than a polygon's solid-angle one, which
    // resampling's weights correct), with the exact radiance.
    bool hasStandIn() const override { return shape_->samplesDirectionsExpensively(); }
    bool sampleStandIn(const LightReference& reference, Vec2 u, float time,
                       LightSample* out) const override;
    Rgb exactRadiance(const LightSample& s) const override { return s.radiance; }
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
    // A sample from the shape's point `s`.
    bool fromShapeSample(const LightReference& reference, const ShapeSample& s,
                         LightSample* out) const;

    const Shape* shape_;
    Rgb radiance_;
    bool twoSided_;
};

}  // namespace rr
