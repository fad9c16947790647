// Affine transforms for placing shapes, in double (they are applied once, at load time, and a
// translation by 10^6 must keep a point's fraction). A thin wrapper over Imath's 4×4 matrix
// (row-vector convention: p' = p · M), so the rest of the renderer never sees Imath types.
#pragma once

#include <Imath/ImathMatrix.h>

#include "math/vector.h"

namespace rr {

class Transform {
  public:
    Transform() = default;

    static Transform translate(const Vec3d& t);
    static Transform scale(const Vec3& s);
    // Rotation by `degrees` about `axis` (right-handed).
    static Transform rotate(const Vec3& axis, double degrees);
    // Row-major 4×4 matrix acting on column vectors, as written in scene files.
    static Transform fromRowMajor(const double m[16]);

    // Applies `this` first, then `next`.
    Transform then(const Transform& next) const;

    Vec3 point(const Vec3d& p) const;  // computed in double, rounded once
    Vec3 vector(const Vec3& v) const;
    Vec3 normal(const Vec3& n) const;  // not normalized

    // The linear part is safely invertible: det finite and |det| > 1e-6 · |r0| |r1| |r2|
    // (relative to Hadamard's bound), so a uniformly tiny or huge scale is not "singular".
    bool isInvertible() const;
    // True when the linear part is a rotation times a uniform scale; returns that scale.
    bool isSimilarity(float* uniformScale) const;

  private:
    Imath::M44d m_;  // p' = p · m_
};

}  // namespace rr
