// Warps from [0,1)² to geometric domains, each with its density. Directions are in a local
// frame with +z as the axis (normal or cone axis). Every warp here has a χ² test.
// Some have an inverse, `…ToSquare`, which gives back the u that the warp maps to a point (for
// TAIS's importance maps over lights' sample coordinates); each has a round-trip test. The
// results are clamped into [0,1)². Where a warp is not injective (the centre of the disk, the
// axis of a sphere or cone, where the azimuth is lost) the inverse returns one of the preimages.
#pragma once

#include "math/vector.h"

namespace rr {

// A point clamped into [0,1)², the warps' domain (inverses round onto its edges and clamp back).
inline Vec2 clampToUnitSquare(Vec2 u) {
    return {clamp(u.x, 0.0f, kOneMinusEpsilon), clamp(u.y, 0.0f, kOneMinusEpsilon)};
}

// Concentric map of the square to the unit disk (Shirley & Chiu 1997); area-preserving up to
// the constant π, so the density on the disk is 1/π.
Vec2 squareToUniformDisk(Vec2 u);
// The inverse of squareToUniformDisk for a point of the unit disk.
Vec2 uniformDiskToSquare(Vec2 p);
inline float uniformDiskPdf() {
    return kInvPi;
}

// Cosine-weighted hemisphere (Malley's method): pdf = cos θ / π.
Vec3 squareToCosineHemisphere(Vec2 u);
inline float cosineHemispherePdf(const Vec3& w) {
    return w.z > 0 ? w.z * kInvPi : 0.0f;
}

Vec3 squareToUniformHemisphere(Vec2 u);
inline float uniformHemispherePdf(const Vec3& w) {
    return w.z >= 0 ? 0.5f * kInvPi : 0.0f;
}

Vec3 squareToUniformSphere(Vec2 u);
// The inverse of squareToUniformSphere for a unit direction: u = ((1 − z)/2, φ/(2π)).
Vec2 uniformSphereToSquare(const Vec3& w);
inline float uniformSpherePdf() {
    return 0.25f * kInvPi;
}

// Uniform directions in the cone cos θ ≥ cos θmax around +z: pdf = 1 / (2π (1 − cos θmax)).
// The cone is given by 1 − cos θmax, which stays accurate for the narrow cones of small,
// distant sphere lights where cos θmax itself rounds to 1.
Vec3 squareToUniformCone(Vec2 u, float oneMinusCosThetaMax);
// The inverse of squareToUniformCone for a unit direction in the cone: u = ((1 − cos θ) /
// (1 − cos θmax), φ/(2π)), with 1 − cos θ = sin² θ/(1 + cos θ) (accurate in narrow cones).
Vec2 uniformConeToSquare(const Vec3& w, float oneMinusCosThetaMax);
inline float uniformConePdf(float oneMinusCosThetaMax) {
    return 1.0f / (kTwoPi * oneMinusCosThetaMax);
}
// 1 − cos θmax of the cone subtended by a sphere with sin² θmax = r² / d².
inline float coneOneMinusCos(float sin2ThetaMax) {
    return sin2ThetaMax / (1.0f + safeSqrt(1.0f - sin2ThetaMax));
}

// Uniform barycentrics (b0, b1) on a triangle (Heitz 2019, low-distortion map);
// b2 = 1 − b0 − b1. The area density is 1 / area.
Vec2 squareToUniformTriangle(Vec2 u);

}  // namespace rr
