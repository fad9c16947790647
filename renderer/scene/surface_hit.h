// What an intersection tells the integrator about a surface point.
#pragma once

#include "math/frame.h"
#include "math/vector.h"
#include "scene/ray.h"

namespace rr {

class Shape;

struct SurfaceHit {
    Vec3 position;
    Vec3 geometricNormal;  // unit; the shape's outward side
    Vec3 shadingNormal;    // unit; same side as geometricNormal
    Vec2 uv;
    float distance = 0;
    float time = 0;
    const Shape* shape = nullptr;

    Frame shadingFrame() const { return Frame(shadingNormal); }

    // A ray leaving this surface in direction `dir` (unit).
    Ray spawn(const Vec3& dir) const {
        return Ray{offsetRayOrigin(position, geometricNormal, dir), dir,
                   std::numeric_limits<float>::infinity(), time};
    }
    // A shadow ray towards `target`, stopping just short of it.
    Ray spawnTo(const Vec3& target) const {
        const Vec3 o = offsetRayOrigin(position, geometricNormal, target - position);
        const Vec3 d = target - o;
        const float dist = length(d);
        return Ray{o, d / dist, dist * (1.0f - 1e-4f), time};
    }
};

}  // namespace rr
