// Parallelogram corner + s·edgeU + t·edgeV, (s, t) ∈ [0,1]²; normal = edgeU × edgeV.
// Intersected as two Embree triangles; uv = (s, t).
#pragma once

#include "scene/shape.h"

namespace rr {

class Quad final : public Shape {
  public:
    Quad(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV);

    RTCGeometry createGeometry(RTCDevice device) const override;
    void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const override;
    float area() const override { return area_; }
    ShapeSample sampleArea(Vec2 u) const override;
    // Sampled by area (the default sampleDirection): u = (s, t) of the point.
    bool invertSampleDirection(const Vec3& reference, const Vec3& point, Vec2* u) const override;
    bool invertsSamples() const override { return !hasMotion(); }

  private:
    Vec3 corner_, edgeU_, edgeV_, normal_;
    Vec3 dualU_, dualV_;  // dot(p − corner, dualU_) = s
    float area_;
    float errorScale_;  // of corner + s·edgeU + t·edgeV
};

}  // namespace rr
