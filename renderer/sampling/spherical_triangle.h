// Spherical triangles: solid angle and uniform sampling (Arvo 1995, "Stratified sampling of
// spherical triangles", SIGGRAPH), for sampling polygonal lights by solid angle (the RIS paper
// cites Arvo for polygons, §2). Vertices are unit vectors; double precision throughout.
#pragma once

#include "math/dvec3.h"

namespace rr {

// Solid angle Ω of the triangle (a, b, c) (Van Oosterom & Strackee 1983):
// tan(Ω/2) = |a · (b × c)| / (1 + a·b + b·c + c·a), stable for small and obtuse triangles.
double sphericalTriangleArea(const DVec3& a, const DVec3& b, const DVec3& c);

// A unit vector distributed uniformly (density 1/area) over the triangle, from u ∈ [0,1)²;
// `area` as sphericalTriangleArea returns.
DVec3 sampleSphericalTriangle(const DVec3& a, const DVec3& b, const DVec3& c, double area, Vec2 u);

}  // namespace rr
