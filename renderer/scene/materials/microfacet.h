// Shared pieces of the half-vector reflection models (Blinn, Cook–Torrance, Ashikhmin–Shirley):
// the half vector, the change of variables from a sampled half vector to the reflected
// direction, power-of-cosine sampling, the V-cavity shadowing-masking term, and the
// two-sided convention (a pair on the lower side is evaluated as its mirror image above).
#pragma once

#include <cmath>

#include "math/vector.h"

namespace rr::microfacet {

// Two-sided materials: wo and wi on the same side are evaluated as if both were above the
// surface (the caller has checked wo.z·wi.z > 0, so |z| mirrors both consistently).
inline Vec3 upperSide(const Vec3& w) {
    return {w.x, w.y, std::abs(w.z)};
}
// Undoes upperSide for a direction sampled above the surface when wo is below.
inline Vec3 toSideOf(const Vec3& wo, const Vec3& w) {
    return {w.x, w.y, wo.z < 0 ? -w.z : w.z};
}

// The half vector h of a reflection pair (both above the surface) and cos θd = wo·h = wi·h,
// computed as |wo + wi|/2: exactly symmetric in wo and wi (so the BRDFs stay reciprocal under
// rounding) and accurate for nearly opposite pairs, where a dot product would cancel.
struct HalfVector {
    Vec3 h;
    float cosD;
};
inline HalfVector halfVector(const Vec3& wo, const Vec3& wi) {
    const Vec3 sum = wo + wi;
    const float len = length(sum);
    return {sum / len, 0.5f * len};
}

// sin² θ of a unit direction from its tangential components: accurate near the normal, where
// 1 − z² would cancel.
inline float sin2Theta(const Vec3& w) {
    return w.x * w.x + w.y * w.y;
}

// cos^e θ of a unit direction above the surface, as exp(e/2 · ln(1 − sin² θ)): stays accurate
// for the exponents of narrow lobes (e = 1000 and beyond), where pow(cos θ, e) would amplify
// the rounding of cos θ near 1.
inline float cosPower(const Vec3& w, float exponent) {
    if (w.z <= 0) return 0;
    const float s2 = sin2Theta(w);
    if (s2 == 0) return 1;
    return std::exp(0.5f * exponent * std::log1p(-std::min(s2, 1.0f)));
}

// A polar angle drawn with cos θ = u^(1/k): density k·cos^(k−1) θ in d(cos θ), i.e.
// (k/2π)·cos^(k−1) θ per steradian with a uniform azimuth. 1 − cos θ comes from expm1 so that
// sin θ keeps its precision for large k. Returns cos θ and stores sin θ.
inline float sampleCosPower(float u, float k, float* sinTheta) {
    const float oneMinusCos = -std::expm1(std::log(u) / k);
    const float cosTheta = 1.0f - oneMinusCos;
    *sinTheta = std::sqrt(std::max(0.0f, oneMinusCos * (2.0f - oneMinusCos)));
    return cosTheta;
}

inline Vec3 sphericalDirection(float sinTheta, float cosTheta, float phi) {
    return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

// Mirror reflection of wo about the microfacet normal h; false when the result is not above
// the surface (that half vector contributes nothing: the sample is declined, and the pdf of
// the reflected directions integrates to less than one by that probability).
inline bool reflectAbove(const Vec3& wo, const Vec3& h, Vec3* wi) {
    *wi = 2.0f * dot(wo, h) * h - wo;
    return wi->z > 0;
}

// Solid-angle density of the reflected direction from the density of the half vector: the
// Jacobian |∂ωh/∂ωi| = 1/(4 |wo·h|) (Torrance & Sparrow 1967; Walter et al. 2007 §4).
inline float reflectedPdf(float halfVectorPdf, const HalfVector& hv) {
    return halfVectorPdf / (4.0f * hv.cosD);
}

// V-cavity shadowing-masking (Torrance & Sparrow 1967; Blinn 1977; Cook & Torrance 1982, the
// geometrical attenuation factor G): each microfacet is one side of a symmetric V groove.
// Symmetric in wo and wi, so the BRDF stays reciprocal.
inline float vCavityG(const Vec3& wo, const Vec3& wi, const HalfVector& hv) {
    const float scale = 2.0f * hv.h.z / hv.cosD;
    return std::min({1.0f, scale * wo.z, scale * wi.z});
}

}  // namespace rr::microfacet
