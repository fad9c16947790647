// Flat disk (centre, unit normal, radius): Embree user geometry, uv = (r / radius, φ / 2π).
#pragma once

#include "math/frame.h"
#include "scene/shape.h"

namespace rr {

class Disk final : public Shape {
  public:
    Disk(const Vec3& center, const Vec3& normal, float radius);

    RTCGeometry createGeometry(RTCDevice device) const override;
    void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const override;
    float area() const override { return kPi * radius_ * radius_; }
    ShapeSample sampleArea(Vec2 u) const override;
    // Sampled by area (the default sampleDirection, concentric map): its inverse at the point.
    bool invertSampleDirection(const Vec3& reference, const Vec3& point, Vec2* u) const override;
    bool invertsSamples() const override { return !hasMotion(); }

    // The user-geometry callbacks (user_geometry.h): bounds at a time step, the ray parameter
    // of the hit with the disk where it is at `time` if within (tMin, tMax), the normal there.
    RTCBounds boundsAt(float timeStep) const;
    bool hitDistance(const Vec3& origin, const Vec3& direction, float time, float tMin, float tMax,
                     float* t) const;
    Vec3 hitNormal(const Vec3&, const Vec3&, float, float) const { return frame_.n; }
    Vec3 centerAt(float time) const { return center_ + offsetAt(time); }
    float radius() const { return radius_; }
    const Vec3& normal() const { return frame_.n; }

  private:
    Vec3 center_;
    Frame frame_;
    float radius_;
    float errorScale_;  // of centre + in-plane offset
};

}  // namespace rr
