// A double-precision 3-vector for the few computations that float cannot carry: polygon plane
// fitting and spherical-triangle sampling (angles from nearly parallel unit vectors).
#pragma once

#include <cmath>

#include "math/vector.h"

namespace rr {

struct DVec3 {
    double x = 0, y = 0, z = 0;
    constexpr DVec3() = default;
    constexpr DVec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit DVec3(const Vec3& v) : x(v.x), y(v.y), z(v.z) {}

    constexpr DVec3 operator+(const DVec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr DVec3 operator-(const DVec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr DVec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    constexpr DVec3 operator/(double s) const { return {x / s, y / s, z / s}; }
    Vec3 toFloat() const { return {float(x), float(y), float(z)}; }
};

constexpr double dot(const DVec3& a, const DVec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr DVec3 cross(const DVec3& a, const DVec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(const DVec3& a) {
    return std::sqrt(dot(a, a));
}
inline DVec3 normalize(const DVec3& a) {
    return a / length(a);
}

}  // namespace rr
