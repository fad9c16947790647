// Linear RGB radiance and reflectance values.
#pragma once

#include <algorithm>
#include <cmath>

namespace rr {

struct Rgb {
    float r = 0, g = 0, b = 0;
    constexpr Rgb() = default;
    constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Rgb(float s) : r(s), g(s), b(s) {}

    float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
    constexpr Rgb operator+(const Rgb& o) const { return {r + o.r, g + o.g, b + o.b}; }
    constexpr Rgb operator-(const Rgb& o) const { return {r - o.r, g - o.g, b - o.b}; }
    constexpr Rgb operator*(const Rgb& o) const { return {r * o.r, g * o.g, b * o.b}; }
    constexpr Rgb operator*(float s) const { return {r * s, g * s, b * s}; }
    constexpr Rgb operator/(float s) const { return *this * (1.0f / s); }
    Rgb& operator+=(const Rgb& o) { return *this = *this + o; }
    Rgb& operator*=(const Rgb& o) { return *this = *this * o; }
    Rgb& operator*=(float s) { return *this = *this * s; }
    constexpr bool operator==(const Rgb& o) const = default;

    bool isBlack() const { return r == 0 && g == 0 && b == 0; }
    float maxComponent() const { return std::max({r, g, b}); }
    // Rec. 709 luminance, as the papers' σ/µ and tvi metrics use.
    float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
    bool isFinite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr Rgb operator*(float s, const Rgb& c) {
    return c * s;
}

}  // namespace rr
