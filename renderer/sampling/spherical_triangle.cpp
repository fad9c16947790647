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

SphericalTriangleSampler::SphericalTriangleSampler(const DVec3& a, const DVec3& b, const DVec3& c,
                                                   double area)
    : a_(a), b_(b), tangentC_(arcTangent(a, c)), area_(area), cosC_(dot(a, b)) {
    const DVec3 tangentB = arcTangent(a, b);
    cosAlpha_ = clampUnit(dot(tangentB, tangentC_));
    sinAlpha_ = length(cross(tangentB, tangentC_));
    alpha_ = std::atan2(sinAlpha_, cosAlpha_);  // the angle at a
}

DVec3 SphericalTriangleSampler::sample(Vec2 u) const {
    // Arvo 1995, §3: choose the sub-triangle (a, b, ĉ) of area u₁·Ω, with ĉ on the arc from a
    // to c, by inverting the area formula for cos of the arc aĉ (q); then a point on the arc
    // from b to ĉ with cos of its distance to b uniform between 1 and b·ĉ.
    const double subArea = double(u.x) * area_;
    const double s = std::sin(subArea - alpha_), t = std::cos(subArea - alpha_);
    const double uu = t - cosAlpha_;
    const double v = s + sinAlpha_ * cosC_;
    const double q = clampUnit(((v * t - uu * s) * cosAlpha_ - v) / ((v * s + uu * t) * sinAlpha_));
    const DVec3 cHat = a_ * q + tangentC_ * std::sqrt(std::max(0.0, 1 - q * q));
    const double z = 1 - double(u.y) * (1 - dot(cHat, b_));
    return b_ * z + arcTangent(b_, cHat) * std::sqrt(std::max(0.0, 1 - z * z));
}

}  // namespace rr
