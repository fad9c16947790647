// Convex planar polygon: vertices v0 … vn−1 (n ≥ 3) in order, normal by the right-hand rule on
// that order. Intersected as the triangle fan (v0, vk, vk+1) on Embree triangles; sampled
// uniformly by area: a fan triangle with probability ∝ its area, then a uniform point in it.
// As an emitter it is the polygonal area light of the RIS paper's fig. 4.
//
// uv: planar coordinates along û = (v1 − v0)/|v1 − v0| and v̂ = n × û, each rescaled to [0, 1]
// over the polygon's extent. A rectangle given as (corner, corner + edge_u, corner + edge_u +
// edge_v, corner + edge_v) thus gets the uv of the equivalent quad.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sampling/distribution1d.h"
#include "scene/shape.h"

namespace rr {

// Why a vertex list is not a convex planar polygon: `vertex` is the offending vertex, or −1
// when the polygon as a whole is at fault (zero area).
struct PolygonProblem {
    int vertex = -1;
    std::string message;
};

// Checks n ≥ 3 vertices with tolerances relative to the polygon's size R (the largest distance
// of a vertex from their mean): area > 1e-6 R², every vertex within 1e-4 R of the plane, no
// vertex repeated (consecutive vertices at least 1e-6 R apart), and the boundary turning the
// same way at every vertex (collinear vertices allowed) and winding around exactly once.
std::optional<PolygonProblem> checkConvexPolygon(std::span<const Vec3> vertices);

class Polygon final : public Shape {
  public:
    // `vertices` must pass checkConvexPolygon; they are projected onto the polygon's plane.
    explicit Polygon(std::span<const Vec3> vertices);

    RTCGeometry createGeometry(RTCDevice device) const override;
    void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const override;
    float area() const override { return area_; }
    ShapeSample sampleArea(Vec2 u) const override;

    const Vec3& normal() const { return normal_; }

  private:
    std::vector<Vec3> vertices_;
    Vec3 normal_;
    Vec3 uvOrigin_, uAxis_, vAxis_;  // uv = (dot(p − uvOrigin_, uAxis_), dot(…, vAxis_))
    float area_ = 0;
    float errorScale_ = 0;
    Distribution1D fanByArea_;  // over the triangles (v0, vk, vk+1), k = 1 … n−2
};

}  // namespace rr
