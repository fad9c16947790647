// Convex planar polygon: vertices v0 … vn−1 (n ≥ 3) in order, normal by the right-hand rule on
// that order. Intersected as the triangle fan (v0, vk, vk+1) on Embree triangles. As an emitter
// it is the polygonal area light of the RIS paper's fig. 4, sampled uniformly in the solid angle
// it subtends (Arvo 1995, which the RIS paper cites): a fan triangle with probability ∝ its
// spherical area, then a uniform direction in that spherical triangle. When it subtends less
// than kMinSolidAngle (far away, or seen edge-on), uniform sampling by area instead: a fan
// triangle with probability ∝ its area, then a uniform point in it. Sampling by area can also
// be chosen outright (PolygonSampling::Area): a worse density at a fraction of the cost, which
// is what resampling wants of its source density (RIS, Talbot et al. 2005 §4.2: "g and p
// should be computationally cheap to sample and evaluate").
//
// uv: planar coordinates along û = (v1 − v0)/|v1 − v0| and v̂ = n × û, each rescaled to [0, 1]
// over the polygon's extent. A rectangle given as (corner, corner + edge_u, corner + edge_u +
// edge_v, corner + edge_v) thus gets the uv of the equivalent quad.
#pragma once

#include <array>
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

enum class PolygonSampling : uint8_t { SolidAngle, Area };

class Polygon final : public Shape {
  public:
    // `vertices` must pass checkConvexPolygon; they are projected onto the polygon's plane.
    explicit Polygon(std::span<const Vec3> vertices,
                     PolygonSampling sampling = PolygonSampling::SolidAngle);

    RTCGeometry createGeometry(RTCDevice device) const override;
    void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const override;
    float area() const override { return area_; }
    ShapeSample sampleArea(Vec2 u) const override;
    bool sampleDirection(const Vec3& reference, Vec2 u, float time,
                         ShapeSample* out) const override;
    float directionPdf(const Vec3& reference, const SurfaceHit& hit) const override;
    const Vec3& normal() const { return normal_; }
    // The solid angle the polygon (displaced by `offset`) subtends at `reference`.
    double solidAngle(const Vec3& reference, const Vec3& offset = Vec3(0.0f)) const;

    // Below this solid angle, sampling by area: it is then nearly uniform in solid angle anyway,
    // and Arvo's inversion loses digits to cancellation (terms of order Ω from terms of order
    // 1; in double precision still ~1e-12 relative at 1e-4 sr).
    static constexpr double kMinSolidAngle = 1e-4;
    // The most vertices a polygon may have (the solid-angle sampler keeps a view of all of
    // them on the stack).
    static constexpr int kMaxVertices = 64;

  private:
    // The fan triangles (v0, vk−1, vk) as seen from one point (polygon.cpp).
    struct FanView;
    // The view from `reference` with the polygon displaced by `offset`: the last few are kept
    // per thread, as resampling's candidates and several light samples per shading point
    // sample one polygon from one point many times.
    FanView& fanView(const Vec3& reference, const Vec3& offset) const;

    std::vector<Vec3> vertices_;
    Vec3 normal_;
    Vec3 uvOrigin_, uAxis_, vAxis_;  // uv = (dot(p − uvOrigin_, uAxis_), dot(…, vAxis_))
    float area_ = 0;
    float errorScale_ = 0;
    Distribution1D fanByArea_;  // over the triangles (v0, vk, vk+1), k = 1 … n−2
    PolygonSampling sampling_;
};

}  // namespace rr
