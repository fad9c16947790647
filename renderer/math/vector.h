// Small fixed-size vector types. Float precision throughout the renderer; the few places that
// need more (sphere intersection, pixel accumulation) use double locally.
#pragma once

#include <algorithm>
#include <cmath>

namespace rr {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kTwoPi = 6.28318530717958647692f;
// The largest float below 1: the upper end of sample coordinates in [0, 1).
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

struct Vec2 {
    float x = 0, y = 0;
    constexpr Vec2() = default;
    constexpr Vec2(float x_, float y_) : x(x_), y(y_) {}
    float operator[](int i) const { return i == 0 ? x : y; }
};

struct Vec3 {
    float x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}

    float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    float& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }

    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3 operator*(float s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3 operator*(const Vec3& o) const { return {x * o.x, y * o.y, z * o.z}; }
    constexpr Vec3 operator/(float s) const { return *this * (1.0f / s); }
    Vec3& operator+=(const Vec3& o) { return *this = *this + o; }
    Vec3& operator-=(const Vec3& o) { return *this = *this - o; }
    Vec3& operator*=(float s) { return *this = *this * s; }
    constexpr bool operator==(const Vec3& o) const = default;
};

constexpr Vec3 operator*(float s, const Vec3& v) {
    return v * s;
}
constexpr float dot(const Vec3& a, const Vec3& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float lengthSquared(const Vec3& v) {
    return dot(v, v);
}
inline float length(const Vec3& v) {
    return std::sqrt(dot(v, v));
}
inline Vec3 normalize(const Vec3& v) {
    return v / length(v);
}
inline float maxAbsComponent(const Vec3& v) {
    return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}
inline Vec3 min(const Vec3& a, const Vec3& b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 max(const Vec3& a, const Vec3& b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
// A position as a scene file gives it, in double: the loader moves it into rendering space
// (loader/camera_reader.h) before rounding to float, so that coordinates far from the world's
// origin lose nothing to the translation.
struct Vec3d {
    double x = 0, y = 0, z = 0;
    constexpr Vec3d operator-() const { return {-x, -y, -z}; }
    constexpr Vec3d operator-(const Vec3d& o) const { return {x - o.x, y - o.y, z - o.z}; }
};

inline Vec3 toFloat(const Vec3d& v) {
    return {float(v.x), float(v.y), float(v.z)};
}

inline bool isFinite(const Vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
// Mirror reflection of w about the normal n (both pointing away from the surface).
inline Vec3 reflect(const Vec3& w, const Vec3& n) {
    return 2.0f * dot(w, n) * n - w;
}

inline float clamp(float v, float lo, float hi) {
    return std::min(std::max(v, lo), hi);
}
inline float safeSqrt(float v) {
    return std::sqrt(std::max(v, 0.0f));
}
inline float safeAcos(float v) {
    return std::acos(clamp(v, -1.0f, 1.0f));
}
inline float square(float v) {
    return v * v;
}

}  // namespace rr
