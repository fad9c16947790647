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

// The azimuth of (x, y) as a fraction of a turn, in [0, 1).
float azimuthFraction(float x, float y) {
    float phi = std::atan2(y, x);
    if (phi < 0) phi += kTwoPi;
    return phi / kTwoPi;
}

}  // namespace

Vec2 squareToUniformDisk(Vec2 u) {
    float r, phi;
    concentricPolar(u, &r, &phi);
    return {r * std::cos(phi), r * std::sin(phi)};
}

Vec2 uniformDiskToSquare(Vec2 p) {
    const float r = std::sqrt(p.x * p.x + p.y * p.y);
    if (r == 0) return {0.5f, 0.5f};
    // The angle of the point in [−3π/4, 5π/4): the four wedges of concentricPolar in turn.
    float theta = std::atan2(p.y, p.x);
    if (theta < -0.75f * kPi) theta += kTwoPi;
    float a, b;
    if (theta < -0.25f * kPi) {  // bottom: b = −r, the point at angle φ + π
        b = -r;
        a = b * (kPi / 2.0f - (theta + kPi)) * (4.0f / kPi);
    } else if (theta <= 0.25f * kPi) {  // right: a = r, φ = θ
        a = r;
        b = a * theta * (4.0f / kPi);
    } else if (theta < 0.75f * kPi) {  // top: b = r, φ = θ
        b = r;
        a = b * (kPi / 2.0f - theta) * (4.0f / kPi);
    } else {  // left: a = −r, the point at angle φ + π
        a = -r;
        b = a * (theta - kPi) * (4.0f / kPi);
    }
    return clampToUnitSquare({(a + 1.0f) / 2.0f, (b + 1.0f) / 2.0f});
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

Vec2 uniformSphereToSquare(const Vec3& w) {
    return clampToUnitSquare({(1.0f - w.z) / 2.0f, azimuthFraction(w.x, w.y)});
}

Vec3 squareToUniformCone(Vec2 u, float oneMinusCosThetaMax) {
    const float oneMinusCos = u.x * oneMinusCosThetaMax;
    const float cosTheta = 1.0f - oneMinusCos;
    const float sinTheta = safeSqrt(oneMinusCos * (2.0f - oneMinusCos));
    const float phi = kTwoPi * u.y;
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

Vec2 uniformConeToSquare(const Vec3& w, float oneMinusCosThetaMax) {
    // In a narrow cone cos θ rounds to 1 and only sin θ carries the angle (as in the warp).
    const float sin2Theta = w.x * w.x + w.y * w.y;
    const float oneMinusCos = w.z > 0 ? sin2Theta / (1.0f + w.z) : 1.0f - w.z;
    return clampToUnitSquare({oneMinusCos / oneMinusCosThetaMax, azimuthFraction(w.x, w.y)});
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
