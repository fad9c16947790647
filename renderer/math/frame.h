// Orthonormal frame used to move directions between world space and a local shading space in
// which the normal is +z (so cos θ = w.z for local directions).
#pragma once

#include "math/vector.h"

namespace rr {

struct Frame {
    Vec3 s, t, n;

    Frame() : s(1, 0, 0), t(0, 1, 0), n(0, 0, 1) {}
    // Builds a frame around a unit normal without branches on the hemisphere sign
    // (Duff et al. 2017, "Building an orthonormal basis, revisited").
    explicit Frame(const Vec3& normal) : n(normal) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Vec3(b, sign + n.y * n.y * a, -n.y);
    }

    // z = `normal` (unit), x = `tangent` made orthogonal to it; falls back to Frame(normal)
    // when the tangent is zero or (nearly) parallel to the normal.
    static Frame fromNormalAndTangent(const Vec3& normal, const Vec3& tangent) {
        const Vec3 inPlane = tangent - normal * dot(normal, tangent);
        const float len2 = lengthSquared(inPlane);
        if (!(len2 > 1e-12f * lengthSquared(tangent))) return Frame(normal);
        Frame f;
        f.n = normal;
        f.s = inPlane / std::sqrt(len2);
        f.t = cross(normal, f.s);
        return f;
    }

    Vec3 toLocal(const Vec3& w) const { return {dot(w, s), dot(w, t), dot(w, n)}; }
    Vec3 toWorld(const Vec3& w) const { return s * w.x + t * w.y + n * w.z; }
};

}  // namespace rr
