// Cook–Torrance reflection with the Beckmann distribution of normals (Cook & Torrance 1982;
// distribution, masking and sampling as in Walter et al. 2007, §5 and §5.1):
//   D(h) = exp(−tan² θh / α²) / (π α² cos⁴ θh), roughness = α,
// and Smith's shadowing-masking for the Beckmann surface as the separable product
// G1(wo)·G1(wi) of the exact G1 (the form with erf, not its rational fit). Smith rather than
// Cook & Torrance's V-cavity: Smith's G follows from the statistics of the Beckmann
// microsurface itself (Heitz 2014), where the V-cavity profile is an assumption independent
// of D. Half vectors are sampled from D·cos θh (tan² θh = −α² ln(1 − u), Walter et al. 2007
// §5.1).
#pragma once

#include "scene/materials/torrance_sparrow.h"

namespace rr {

// The Beckmann distribution D(h) for roughness α (zero below the surface).
float beckmannD(const Vec3& h, float alpha);
// Smith's masking G1(w, h) of the Beckmann surface for a direction w above it.
float beckmannSmithG1(const Vec3& w, const Vec3& h, float alpha);

struct BeckmannDistribution {
    static float fromRoughness(float roughness) { return roughness; }
    static float D(const Vec3& h, float alpha) { return beckmannD(h, alpha); }
    static float G(const Vec3& wo, const Vec3& wi, const microfacet::HalfVector& hv, float alpha) {
        return beckmannSmithG1(wo, hv.h, alpha) * beckmannSmithG1(wi, hv.h, alpha);
    }
    static Vec3 sampleHalfVector(Vec2 u, float alpha);
};

// `roughness` = Beckmann α in (0, 2]; `eta` is the index of refraction under the surface.
class CookTorrance final : public TorranceSparrow<BeckmannDistribution> {
  public:
    using TorranceSparrow::TorranceSparrow;
};

}  // namespace rr
