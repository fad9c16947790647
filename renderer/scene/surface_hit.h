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
    // Direction of increasing u on the surface (∂p/∂u, any length), or zero where the shape has
    // none. Anisotropic materials orient their u axis along it.
    Vec3 tangent;
    float distance = 0;
    float time = 0;
    float errorScale = 0;  // magnitude of the coordinates `position` was computed from
    const Shape* shape = nullptr;

    // The local shading frame: z = shading normal, x = the tangent projected onto the tangent
    // plane (an arbitrary but continuous-per-normal axis where there is no usable tangent).
    Frame shadingFrame() const { return Frame::fromNormalAndTangent(shadingNormal, tangent); }

    // A ray leaving this surface in direction `dir` (unit).
    Ray spawn(const Vec3& dir) const {
        return Ray{offsetRayOrigin(position, geometricNormal, dir, errorScale), dir,
                   std::numeric_limits<float>::infinity(), time};
    }
    // A shadow ray to a point on a light (normal and error scale of that point; a zero normal
    // for point lights). Both ends are lifted off their surfaces, so the ray neither re-hits
    // this surface nor the light's, and sees occluders however close to either end.
    Ray spawnTo(const Vec3& target, const Vec3& targetNormal, float targetErrorScale) const {
        const Vec3 from = offsetRayOrigin(position, geometricNormal, target - position, errorScale);
        const Vec3 to = offsetRayOrigin(target, targetNormal, position - target, targetErrorScale);
        const Vec3 d = to - from;
        const float dist = length(d);
        return Ray{from, d / dist, dist, time};
    }
};

}  // namespace rr
