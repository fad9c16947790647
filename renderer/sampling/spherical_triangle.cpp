#include "sampling/spherical_triangle.h"

#include <algorithm>

namespace rr {

namespace {

// The unit tangent at `from` of the great arc towards `to`.
DVec3 arcTangent(const DVec3& from, const DVec3& to) {
    return normalize(to - from * dot(from, to));
}

double clampUnit(double x) {
    return std::clamp(x, -1.0, 1.0);
}

}  // namespace

double sphericalTriangleArea(const DVec3& a, const DVec3& b, const DVec3& c) {
    const double triple = std::abs(dot(a, cross(b, c)));
    return 2 * std::atan2(triple, 1 + dot(a, b) + dot(b, c) + dot(c, a));
}

DVec3 sampleSphericalTriangle(const DVec3& a, const DVec3& b, const DVec3& c, double area, Vec2 u) {
    // Arvo 1995, §3: choose the sub-triangle (a, b, ĉ) of area u₁·Ω, with ĉ on the arc from a
    // to c, by inverting the area formula for cos of the arc aĉ (q); then a point on the arc
    // from b to ĉ with cos of its distance to b uniform between 1 and b·ĉ.
    const DVec3 tb = arcTangent(a, b), tc = arcTangent(a, c);
    const double cosAlpha = clampUnit(dot(tb, tc)), sinAlpha = length(cross(tb, tc));
    const double alpha = std::atan2(sinAlpha, cosAlpha);  // the angle at a
    const double subArea = double(u.x) * area;
    const double s = std::sin(subArea - alpha), t = std::cos(subArea - alpha);
    const double uu = t - cosAlpha;
    const double v = s + sinAlpha * dot(a, b);  // dot(a, b) = cos of the side c
    const double q = clampUnit(((v * t - uu * s) * cosAlpha - v) / ((v * s + uu * t) * sinAlpha));
    const DVec3 cHat = a * q + tc * std::sqrt(std::max(0.0, 1 - q * q));
    const double z = 1 - double(u.y) * (1 - dot(cHat, b));
    return b * z + arcTangent(b, cHat) * std::sqrt(std::max(0.0, 1 - z * z));
}

}  // namespace rr
