#include "scene/materials/cook_torrance.h"

#include "scene/materials/dielectric.h"
#include "scene/materials/microfacet.h"

namespace rr {

using namespace microfacet;

float beckmannD(const Vec3& h, float alpha) {
    if (h.z <= 0) return 0;
    const float cos2 = h.z * h.z;
    const float tan2 = sin2Theta(h) / cos2;
    const float alpha2 = alpha * alpha;
    const float e = std::exp(-tan2 / alpha2);
    // Where the exponential underflows D is zero; testing it first avoids 0/0 when cos⁴ θh
    // underflows too.
    if (e == 0) return 0;
    return e / (kPi * alpha2 * cos2 * cos2);
}

float beckmannSmithG1(const Vec3& w, const Vec3& h, float alpha) {
    if (dot(w, h) <= 0) return 0;  // χ⁺(w·h / w·n): the facet faces away from w
    const float sinTheta = std::sqrt(sin2Theta(w));
    if (sinTheta == 0) return 1;
    const float a = w.z / (alpha * sinTheta);  // 1 / (α tan θ)
    // Walter et al. 2007 §5.1: 2 / (1 + erf(a) + exp(−a²) / (a √π)).
    return 2.0f / (1.0f + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(kPi)));
}

float beckmannReflectedPdf(const Vec3& wo, const Vec3& wi, float alpha) {
    const HalfVector hv = halfVector(wo, wi);
    return reflectedPdf(beckmannD(hv.h, alpha) * hv.h.z, hv);
}

Rgb CookTorrance::evalUpper(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const float alpha = roughness_->eval(ctx);
    const HalfVector hv = halfVector(wo, wi);
    const float d = beckmannD(hv.h, alpha);
    if (d == 0) return Rgb(0.0f);
    const float g = beckmannSmithG1(wo, hv.h, alpha) * beckmannSmithG1(wi, hv.h, alpha);
    const float f = fresnelDielectric(hv.cosD, eta_);
    // f·cos θi = R·D·G·F / (4 cos θo): the cos θi of the denominator cancels.
    return reflectance_->eval(ctx) * (d * g * f / (4.0f * wo.z));
}

Rgb CookTorrance::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);
    return evalUpper(ctx, upperSide(wo), upperSide(wi));
}

float CookTorrance::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return beckmannReflectedPdf(upperSide(wo), upperSide(wi), roughness_->eval(ctx));
}

bool CookTorrance::sample(const ShadingContext& ctx, const Vec3& wo, float, Vec2 uDirection,
                          BsdfSample* out) const {
    if (wo.z == 0) return false;
    const Vec3 o = upperSide(wo);
    const float alpha = roughness_->eval(ctx);
    // Walter et al. 2007 §5.1: tan² θh = −α² ln(1 − u1), φh = 2π u2.
    const float tan2 = -alpha * alpha * std::log1p(-uDirection.x);
    const float cosTheta = 1.0f / std::sqrt(1.0f + tan2);
    const float sinTheta = std::sqrt(tan2) * cosTheta;
    const Vec3 h = sphericalDirection(sinTheta, cosTheta, kTwoPi * uDirection.y);
    Vec3 wi;
    if (!reflectAbove(o, h, &wi)) return false;
    const float pdf = beckmannReflectedPdf(o, wi, alpha);
    if (!(pdf > 0)) return false;
    out->wi = toSideOf(wo, wi);
    out->pdf = pdf;
    out->weight = evalUpper(ctx, o, wi) / pdf;
    out->eta = 1;
    out->lobe = kReflection | kGlossy;
    return true;
}

void CookTorrance::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(Vec3(-wo.x, -wo.y, wo.z));  // the mirror direction
}

}  // namespace rr
