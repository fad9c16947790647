#pragma once

#include <limits>

#include "math/vector.h"

namespace rr {

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length
    float tMax = std::numeric_limits<float>::infinity();
    float time = 0;  // scene time in [0, 1] (motion blur); 0 for static scenes
};

// Relative size of the offset that lifts a point off its surface. A surface point computed in
// float from coordinates of magnitude `errorScale` (vertices, centre and radius, corner and
// edges) is off the true surface by a few ulps of that magnitude, ~1e-7 relative; the offset is
// about a hundred times that, yet small against any feature the scene resolves.
inline constexpr float kRayOffset = 1e-5f;

// Moves p off its surface along the geometric normal, to the side `towards` points to.
// (Scale-aware rather than absolute, so a scene in millimetres behaves as one in metres.)
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& geometricNormal, const Vec3& towards,
                            float errorScale) {
    const float eps = kRayOffset * errorScale;
    return dot(towards, geometricNormal) >= 0 ? p + geometricNormal * eps
                                              : p - geometricNormal * eps;
}

}  // namespace rr
