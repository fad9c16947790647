// Analytic sphere: Embree user geometry with a double-precision quadratic so glass balls get
// exact hit points and normals (n = (p − c) / r). Lights on spheres are sampled by the cone of
// directions they subtend (uniform solid angle) when the reference point is outside.
// Texture coordinates are spherical angles about the sphere's own z axis (its poles), which a
// rotation in the shape's transform turns: u = φ/2π, v = θ/π, and the tangent runs along the
// parallels (the u axis of anisotropic materials).
#pragma once

#include "math/frame.h"
#include "scene/shape.h"

namespace rr {

class Sphere final : public Shape {
  public:
    // `orientation`: the sphere's own axes in world space (z = the poles of its uv).
    Sphere(const Vec3& center, float radius, const Frame& orientation = Frame())
        : center_(center),
          radius_(radius),
          errorScale_(maxAbsComponent(center) + radius),
          orientation_(orientation) {}

    RTCGeometry createGeometry(RTCDevice device) const override;
    void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const override;
    float area() const override { return 4.0f * kPi * radius_ * radius_; }
    ShapeSample sampleArea(Vec2 u) const override;
    bool sampleDirection(const Vec3& reference, Vec2 u, float time,
                         ShapeSample* out) const override;
    float directionPdf(const Vec3& reference, const SurfaceHit& hit) const override;
    // From outside, the u of the point's direction in the cone (the point is used only through
    // its direction: a point on the far side gives the u of the near one in front of it); from
    // inside, the inverse of area sampling (uniform on the sphere) at the point's normal.
    bool invertSampleDirection(const Vec3& reference, const Vec3& point, Vec2* u) const override;
    bool invertsSamples() const override { return !hasMotion(); }

    Vec3 centerAt(float time) const { return center_ + offsetAt(time); }
    float radius() const { return radius_; }

    // The user-geometry callbacks (user_geometry.h). hitDistance: the nearest t in
    // (tMin, tMax) where the ray meets the sphere at `time`; the quadratic is solved in double
    // precision with the numerically stable root form.
    RTCBounds boundsAt(float timeStep) const;
    bool hitDistance(const Vec3& origin, const Vec3& direction, float time, float tMin, float tMax,
                     float* t) const;
    Vec3 hitNormal(const Vec3& origin, const Vec3& direction, float time, float t) const;

  private:
    // Whether sampleDirection samples the cone the sphere subtends from a reference point at
    // squared distance `dist2` from the centre (outside it, with a margin), not by area.
    bool samplesCone(float dist2) const { return dist2 > radius_ * radius_ * (1.0f + 1e-4f); }

    Vec3 center_;
    float radius_;
    float errorScale_;  // of centre + radius · normal
    Frame orientation_;
};

}  // namespace rr
