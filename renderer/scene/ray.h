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

// Offsets a ray origin off a surface to avoid re-hitting it: along the geometric normal, to the
// side `towards` points to, by an amount that grows with the coordinates' magnitude (float
// rounding error of the hit point is relative to it).
inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& geometricNormal, const Vec3& towards) {
    const float eps = 1e-5f * (1.0f + maxAbsComponent(p));
    return dot(towards, geometricNormal) >= 0 ? p + geometricNormal * eps
                                              : p - geometricNormal * eps;
}

}  // namespace rr
