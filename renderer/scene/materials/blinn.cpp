#include "scene/materials/blinn.h"

#include "scene/materials/dielectric.h"
#include "scene/materials/microfacet.h"

namespace rr {

using namespace microfacet;

float blinnD(const Vec3& h, float exponent) {
    return (exponent + 2.0f) * (0.5f * kInvPi) * cosPower(h, exponent);
}

Rgb Blinn::evalUpper(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const HalfVector hv = halfVector(wo, wi);
    const float d = blinnD(hv.h, exponent(ctx));
    if (d == 0) return Rgb(0.0f);
    const float g = vCavityG(wo, wi, hv);
    const float f = fresnelDielectric(hv.cosD, eta_);
    // f·cos θi = R·D·G·F / (4 cos θo): the cos θi of the denominator cancels.
    return reflectance_->eval(ctx) * (d * g * f / (4.0f * wo.z));
}

float Blinn::pdfUpper(float e, const Vec3& wo, const Vec3& wi) const {
    const HalfVector hv = halfVector(wo, wi);
    return reflectedPdf(blinnD(hv.h, e) * hv.h.z, hv);
}

Rgb Blinn::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);
    return evalUpper(ctx, upperSide(wo), upperSide(wi));
}

float Blinn::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return pdfUpper(exponent(ctx), upperSide(wo), upperSide(wi));
}

bool Blinn::sample(const ShadingContext& ctx, const Vec3& wo, float, Vec2 uDirection,
                   BsdfSample* out) const {
    if (wo.z == 0) return false;
    const Vec3 o = upperSide(wo);
    const float e = exponent(ctx);
    // D(h) cos θh = (e + 2)/(2π) cos^(e+1) θh: cos θh = u^(1/(e+2)), uniform azimuth.
    float sinTheta;
    const float cosTheta = sampleCosPower(uDirection.x, e + 2.0f, &sinTheta);
    const Vec3 h = sphericalDirection(sinTheta, cosTheta, kTwoPi * uDirection.y);
    Vec3 wi;
    if (!reflectAbove(o, h, &wi)) return false;
    const float pdf = pdfUpper(e, o, wi);
    if (!(pdf > 0)) return false;
    out->wi = toSideOf(wo, wi);
    out->pdf = pdf;
    out->weight = evalUpper(ctx, o, wi) / pdf;
    out->eta = 1;
    out->lobe = kReflection | kGlossy;
    return true;
}

void Blinn::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(Vec3(-wo.x, -wo.y, wo.z));  // the mirror direction (two-stage §2.2)
}

}  // namespace rr
