#include "scene/materials/ashikhmin_shirley.h"

#include "sampling/warps.h"
#include "scene/materials/microfacet.h"

namespace rr {

using namespace microfacet;

namespace {

float pow5(float x) {
    const float x2 = x * x;
    return x2 * x2 * x;
}

// The exponent n_u cos² φh + n_v sin² φh of the half vector h; at the normal any exponent
// gives cos^n θh = 1.
float halfVectorExponent(const Vec3& h, float nu, float nv) {
    const float s2 = sin2Theta(h);
    return s2 > 0 ? (nu * h.x * h.x + nv * h.y * h.y) / s2 : nu;
}

// Their half-vector density p_h(h) = √((n_u+1)(n_v+1)) / (2π) · cos^(n(φh)) θh, normalised
// over the hemisphere.
float halfVectorPdf(const Vec3& h, float nu, float nv) {
    return std::sqrt((nu + 1.0f) * (nv + 1.0f)) * (0.5f * kInvPi) *
           cosPower(h, halfVectorExponent(h, nu, nv));
}

// A half vector from p_h (their §3): in the first quadrant
// φ = arctan(√((n_u+1)/(n_v+1)) tan(π ξ/2)), mirrored into the quadrant u.x picks; then
// cos θh = u^(1/(n(φ)+1)).
Vec3 sampleHalfVector(Vec2 u, float nu, float nv) {
    const float scaled = 4.0f * u.x;
    const int quadrant = std::min(int(scaled), 3);
    const float t = scaled - float(quadrant);
    float phi = std::atan(std::sqrt((nu + 1.0f) / (nv + 1.0f)) * std::tan(0.5f * kPi * t));
    // p_h depends on φ only through cos² φ and sin² φ: mirror into the other quadrants.
    if (quadrant == 1 || quadrant == 3) phi = -phi;
    if (quadrant == 1 || quadrant == 2) phi += kPi;
    const float cosPhi = std::cos(phi), sinPhi = std::sin(phi);
    const float exponent = nu * cosPhi * cosPhi + nv * sinPhi * sinPhi;
    float sinTheta;
    const float cosTheta = sampleCosPower(u.y, exponent + 1.0f, &sinTheta);
    return {sinTheta * cosPhi, sinTheta * sinPhi, cosTheta};
}

// f·cos θi for wo, wi above the surface.
Rgb evalUpper(const AshikhminShirley::Parameters& p, const Vec3& wo, const Vec3& wi) {
    const HalfVector hv = halfVector(wo, wi);
    const Rgb fresnel = p.rs + (Rgb(1.0f) - p.rs) * pow5(1.0f - hv.cosD);
    // ρs = p_h / (4 k·h) · F / max(cos θo, cos θi).
    const Rgb specular =
        fresnel * (reflectedPdf(halfVectorPdf(hv.h, p.nu, p.nv), hv) / std::max(wo.z, wi.z));
    // ρd: the (1 − Rs) factor and the two Fresnel-like falloffs keep the sum energy-conserving.
    const float falloff = (1.0f - pow5(1.0f - 0.5f * wo.z)) * (1.0f - pow5(1.0f - 0.5f * wi.z));
    const Rgb diffuse = p.rd * (Rgb(1.0f) - p.rs) * (28.0f / (23.0f * kPi) * falloff);
    return (specular + diffuse) * wi.z;
}

float pdfUpper(const AshikhminShirley::Parameters& p, const Vec3& wo, const Vec3& wi) {
    const HalfVector hv = halfVector(wo, wi);
    const float specular = reflectedPdf(halfVectorPdf(hv.h, p.nu, p.nv), hv);
    return p.specularProbability * specular + (1.0f - p.specularProbability) * wi.z * kInvPi;
}

}  // namespace

AshikhminShirley::Parameters AshikhminShirley::at(const ShadingContext& ctx) const {
    Parameters p;
    p.rd = diffuse_->eval(ctx);
    p.rs = specular_->eval(ctx);
    const float u = u_->eval(ctx), v = v_->eval(ctx);
    p.nu = exponents_ ? u : 1.0f / u;
    p.nv = exponents_ ? v : 1.0f / v;
    // Lobe choice in proportion to the terms' reflectances (Rs, and Rd scaled by ρd's
    // 1 − Rs), kept within [0.1, 0.9]: Schlick's F makes the specular term non-zero even for
    // Rs = 0, and the cosine strategy keeps the mixture's support the whole hemisphere. Any
    // probability in (0, 1) is unbiased; this one only steers the variance.
    const float s = p.rs.luminance(), d = p.rd.luminance() * (1.0f - s);
    p.specularProbability = clamp(s + d > 0 ? s / (s + d) : 0.5f, 0.1f, 0.9f);
    return p;
}

Rgb AshikhminShirley::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);
    return evalUpper(at(ctx), upperSide(wo), upperSide(wi));
}

float AshikhminShirley::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return pdfUpper(at(ctx), upperSide(wo), upperSide(wi));
}

bool AshikhminShirley::sample(const ShadingContext& ctx, const Vec3& wo, float uLobe,
                              Vec2 uDirection, BsdfSample* out) const {
    if (wo.z == 0) return false;
    const Parameters p = at(ctx);
    const Vec3 o = upperSide(wo);
    const bool specular = uLobe < p.specularProbability;
    Vec3 wi;
    if (specular) {
        if (!reflectAbove(o, sampleHalfVector(uDirection, p.nu, p.nv), &wi)) return false;
    } else {
        wi = squareToCosineHemisphere(uDirection);
        if (wi.z <= 0) return false;
    }
    const float pdf = pdfUpper(p, o, wi);
    if (!(pdf > 0)) return false;
    out->wi = toSideOf(wo, wi);
    out->pdf = pdf;
    out->weight = evalUpper(p, o, wi) / pdf;  // the mixture's pdf: one estimator, both lobes
    out->eta = 1;
    out->lobe = kReflection | (specular ? kGlossy : kDiffuse);
    return true;
}

// Two-stage §2.2: the mirror direction, and for strong anisotropy (an exponent ratio above 3)
// nine peaks along the cone the specular lobe stretches over. With n_u ≫ n_v the half vectors
// stay near the v–n plane (h_u ≈ 0), so the reflected directions keep the mirror direction's
// u component r_u: peak_i = (r_u, cos(πi/8) √(r_v² + r_n²), sin(πi/8) √(r_v² + r_n²)), and
// symmetrically with u and v exchanged. The paper states this case as "n_u < n_v": its
// parameters there are pbrt's roughnesses (1/n), the ones its fig. 8 quotes.
void AshikhminShirley::peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const {
    const Vec3 mirror(-wo.x, -wo.y, wo.z);
    out->add(mirror);
    const Parameters p = at(ctx);
    const bool alongU = p.nu > 3.0f * p.nv, alongV = p.nv > 3.0f * p.nu;
    if (!alongU && !alongV) return;
    const Vec3 r = upperSide(mirror);
    const float radius =
        alongU ? std::sqrt(r.y * r.y + r.z * r.z) : std::sqrt(r.x * r.x + r.z * r.z);
    for (int i = 0; i <= 8; ++i) {
        const float angle = kPi * float(i) / 8.0f;
        // (the clamp keeps peak 8 on the horizon: sin π rounds below zero in float)
        const float c = radius * std::cos(angle), s = radius * std::max(0.0f, std::sin(angle));
        out->add(toSideOf(wo, alongU ? Vec3(r.x, c, s) : Vec3(c, r.y, s)));
    }
}

}  // namespace rr
