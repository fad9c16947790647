#include "scene/media/henyey_greenstein.h"

#include <cmath>

#include "math/frame.h"

namespace rr {

float HenyeyGreenstein::density(float cosTheta) const {
    const float denominator = 1.0f + g_ * g_ - 2.0f * g_ * cosTheta;
    return (1.0f - g_ * g_) / (4.0f * kPi * denominator * std::sqrt(denominator));
}

float HenyeyGreenstein::eval(const Vec3& wo, const Vec3& wi) const {
    return density(-dot(wo, wi));
}

float HenyeyGreenstein::pdf(const Vec3& wo, const Vec3& wi) const {
    return density(-dot(wo, wi));
}

// The CDF of cos θ is P(x) = (1 − g²)/(2g) · [(1 + g² − 2gx)^{−1/2} − 1/(1 + g)], whose usual
// inverse cos θ = (1 + g² − ((1 − g²)/(1 − g + 2gξ))²) / (2g) divides by g. With a = 2ξ − 1
// it simplifies to the form below, which has no 1/g: exact at g = 0 (cos θ = a, uniform) and
// free of cancellation for small |g|, so no special case is needed.
float HenyeyGreenstein::sampleCosTheta(float xi) const {
    const float a = 2.0f * xi - 1.0f;
    const float b = 1.0f + g_ * a;
    const float numerator = (a + g_) * b + 0.5f * g_ * (1.0f - a * a) * (1.0f - g_ * g_);
    return clamp(numerator / (b * b), -1.0f, 1.0f);
}

float HenyeyGreenstein::sample(const Vec3& wo, Vec2 u, Vec3* wi) const {
    const float cosTheta = sampleCosTheta(u.x);
    const float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    const float phi = kTwoPi * u.y;
    // θ is measured from the forward direction −wo.
    const Frame forward(-wo);
    *wi = normalize(
        forward.toWorld(Vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta)));
    return density(-dot(wo, *wi));
}

}  // namespace rr
