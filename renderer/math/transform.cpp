#include "math/transform.h"

#include <cmath>

namespace rr {

namespace {
Imath::V3d toImath(const Vec3& v) {
    return {v.x, v.y, v.z};
}
Imath::V3d toImath(const Vec3d& v) {
    return {v.x, v.y, v.z};
}
Vec3 fromImath(const Imath::V3d& v) {
    return {float(v.x), float(v.y), float(v.z)};
}
}  // namespace

Transform Transform::translate(const Vec3d& t) {
    Transform r;
    r.m_.setTranslation(toImath(t));
    return r;
}

Transform Transform::scale(const Vec3& s) {
    Transform r;
    r.m_.setScale(toImath(s));
    return r;
}

Transform Transform::rotate(const Vec3& axis, double degrees) {
    Transform r;
    r.m_.setAxisAngle(toImath(normalize(axis)), degrees * M_PI / 180.0);
    return r;
}

Transform Transform::fromRowMajor(const double m[16]) {
    // A row-major matrix for column vectors is the transpose of Imath's row-vector layout.
    Transform r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            r.m_[j][i] = m[4 * i + j];
    return r;
}

Transform Transform::then(const Transform& next) const {
    Transform r;
    r.m_ = m_ * next.m_;
    return r;
}

Vec3 Transform::point(const Vec3d& p) const {
    Imath::V3d out;
    m_.multVecMatrix(toImath(p), out);
    return fromImath(out);
}

Vec3 Transform::vector(const Vec3& v) const {
    Imath::V3d out;
    m_.multDirMatrix(toImath(v), out);
    return fromImath(out);
}

Vec3 Transform::normal(const Vec3& n) const {
    // Normals transform by the inverse transpose of the linear part.
    const Imath::M44d invT = m_.inverse().transposed();
    Imath::V3d out;
    invT.multDirMatrix(toImath(n), out);
    return fromImath(out);
}

bool Transform::isInvertible() const {
    // In double: the products of three entries neither overflow nor underflow.
    double a[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            a[i][j] = m_[i][j];
    const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                       a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                       a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    // Hadamard: |det| <= |r0| |r1| |r2| (rows of the 3×3 part; m_'s rows are the columns of
    // the scene file's matrix, and the bound holds for either), with equality for orthogonal
    // rows. A relative test accepts any unit; an absolute one would call {"scale": 0.0001}
    // (det 1e-12) singular.
    double hadamard = 1;
    for (const auto& row : a)
        hadamard *= std::sqrt(row[0] * row[0] + row[1] * row[1] + row[2] * row[2]);
    return std::isfinite(det) && std::isfinite(hadamard) && std::abs(det) > 1e-6 * hadamard;
}

bool Transform::isSimilarity(float* uniformScale) const {
    const Vec3 rows[3] = {{float(m_[0][0]), float(m_[0][1]), float(m_[0][2])},
                          {float(m_[1][0]), float(m_[1][1]), float(m_[1][2])},
                          {float(m_[2][0]), float(m_[2][1]), float(m_[2][2])}};
    const float s = length(rows[0]);
    constexpr float kTol = 1e-4f;
    for (int i = 0; i < 3; ++i) {
        if (std::abs(length(rows[i]) - s) > kTol * s) return false;
        for (int j = i + 1; j < 3; ++j)
            if (std::abs(dot(rows[i], rows[j])) > kTol * s * s) return false;
    }
    if (uniformScale) *uniformScale = s;
    return s > 0;
}

}  // namespace rr
