// Torrance–Sparrow reflection with the Blinn–Phong distribution of normals (Blinn 1977):
//   D(h) = (e + 2)/(2π) · cos^e θh,
// normalised so that ∫ D cos θh dω = 1, and the V-cavity shadowing-masking term G of Blinn and
// Cook & Torrance. The exponent is e = 1/roughness, pbrt-v1's convention, which the two-stage
// paper used ("Blinn, roughness 0.02" is e = 50). Half vectors are sampled from D·cos θh.
#pragma once

#include "scene/materials/torrance_sparrow.h"

namespace rr {

struct BlinnPhongDistribution {
    static float fromRoughness(float roughness) { return 1.0f / roughness; }
    static float D(const Vec3& h, float exponent);
    static float G(const Vec3& wo, const Vec3& wi, const microfacet::HalfVector& hv, float) {
        return microfacet::vCavityG(wo, wi, hv);
    }
    static Vec3 sampleHalfVector(Vec2 u, float exponent);
};

class Blinn final : public TorranceSparrow<BlinnPhongDistribution> {
  public:
    // `roughness` in (0, 1]; `eta` is the index of refraction under the surface.
    using TorranceSparrow::TorranceSparrow;
    // The Blinn–Phong exponent at a shading point: e = 1/roughness.
    float exponent(const ShadingContext& ctx) const { return parameter(ctx); }
};

}  // namespace rr
