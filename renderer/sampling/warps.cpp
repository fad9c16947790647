#include "sampling/warps.h"

#include <cmath>

namespace rr {

namespace {

// Shirley–Chiu concentric map in polar form; r may be negative (the point is then at angle
// φ + π), which keeps the map continuous.
void concentricPolar(Vec2 u, float* r, float* phi) {
    const float a = 2.0f * u.x - 1.0f;
    const float b = 2.0f * u.y - 1.0f;
    if (a == 0 && b == 0) {
        *r = 0;
        *phi = 0;
    } else if (std::abs(a) > std::abs(b)) {
        *r = a;
        *phi = (kPi / 4.0f) * (b / a);
    } else {
        *r = b;
        *phi = kPi / 2.0f - (kPi / 4.0f) * (a / b);
    }
}

}  // namespace

Vec2 squareToUniformDisk(Vec2 u) {
    float r, phi;
    concentricPolar(u, &r, &phi);
    return {r * std::cos(phi), r * std::sin(phi)};
}

Vec3 squareToCosineHemisphere(Vec2 u) {
    float r, phi;
    concentricPolar(u, &r, &phi);
    // z = √(1 − r²) as √((1 − |r|)(1 + |r|)): accurate near the horizon, where 1 − x² − y²
    // cancels catastrophically.
    const float ar = std::abs(r);
    return {r * std::cos(phi), r * std::sin(phi), safeSqrt((1.0f - ar) * (1.0f + ar))};
}

Vec3 squareToUniformHemisphere(Vec2 u) {
    const float z = u.x;
    const float r = safeSqrt(1.0f - z * z);
    const float phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 squareToUniformSphere(Vec2 u) {
    const float z = 1.0f - 2.0f * u.x;
    const float r = safeSqrt(1.0f - z * z);
    const float phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

Vec3 squareToUniformCone(Vec2 u, float oneMinusCosThetaMax) {
    const float oneMinusCos = u.x * oneMinusCosThetaMax;
    const float cosTheta = 1.0f - oneMinusCos;
    const float sinTheta = safeSqrt(oneMinusCos * (2.0f - oneMinusCos));
    const float phi = kTwoPi * u.y;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

Vec2 squareToUniformTriangle(Vec2 u) {
    float b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2;
        b0 = u.x - b1;
    }
    return {b0, b1};
}

}  // namespace rr
