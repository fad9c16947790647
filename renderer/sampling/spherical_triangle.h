// Spherical triangles: solid angle and uniform sampling (Arvo 1995, "Stratified sampling of
// spherical triangles", SIGGRAPH), for sampling polygonal lights by solid angle (the RIS paper
// cites Arvo for polygons, §2). Vertices are unit vectors; double precision throughout.
#pragma once

#include "math/dvec3.h"
#include "math/vector.h"

namespace rr {

// Solid angle Ω of the triangle (a, b, c) (Van Oosterom & Strackee 1983):
// tan(Ω/2) = |a · (b × c)| / (1 + a·b + b·c + c·a), stable for small and obtuse triangles.
double sphericalTriangleArea(const DVec3& a, const DVec3& b, const DVec3& c);

// Arvo's sampler of one triangle: what does not depend on u (the angle at a, the tangents) is
// computed once, so that many samples from one point (resampling's candidates, several light
// samples per shading point) pay only for the inversion.
class SphericalTriangleSampler {
  public:
    SphericalTriangleSampler() = default;
    // `area` as sphericalTriangleArea returns for (a, b, c).
    SphericalTriangleSampler(const DVec3& a, const DVec3& b, const DVec3& c, double area);
    // A unit vector distributed uniformly (density 1/area) over the triangle, from u ∈ [0,1)².
    DVec3 sample(Vec2 u) const;

  private:
    DVec3 a_, b_, tangentC_;  // tangentC_: the unit tangent at a of the arc towards c
    double area_ = 0, alpha_ = 0, cosAlpha_ = 0, sinAlpha_ = 0, cosC_ = 0;
};

}  // namespace rr
