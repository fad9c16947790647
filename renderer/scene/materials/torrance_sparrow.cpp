#include "scene/materials/torrance_sparrow.h"

#include "scene/materials/blinn.h"
#include "scene/materials/cook_torrance.h"
#include "scene/materials/dielectric.h"

namespace rr {

using namespace microfacet;

template <class D>
Rgb TorranceSparrow<D>::evalUpper(const ShadingContext& ctx, float p, const Vec3& wo,
                                  const Vec3& wi) const {
    const HalfVector hv = halfVector(wo, wi);
    const float d = D::D(hv.h, p);
    if (d == 0) return Rgb(0.0f);
    const float g = D::G(wo, wi, hv, p);
    const float f = fresnelDielectric(hv.cosD, eta_);
    // f·cos θi = R·D·G·F / (4 cos θo): the cos θi of the denominator cancels.
    return reflectance_->eval(ctx) * (d * g * f / (4.0f * wo.z));
}

template <class D>
float TorranceSparrow<D>::pdfUpper(float p, const Vec3& wo, const Vec3& wi) {
    const HalfVector hv = halfVector(wo, wi);
    return reflectedPdf(D::D(hv.h, p) * hv.h.z, hv);
}

template <class D>
Rgb TorranceSparrow<D>::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);
    return evalUpper(ctx, parameter(ctx), upperSide(wo), upperSide(wi));
}

template <class D>
float TorranceSparrow<D>::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return pdfUpper(parameter(ctx), upperSide(wo), upperSide(wi));
}

template <class D>
bool TorranceSparrow<D>::sample(const ShadingContext& ctx, const Vec3& wo, float, Vec2 uDirection,
                                BsdfSample* out) const {
    if (wo.z == 0) return false;
    const Vec3 o = upperSide(wo);
    const float p = parameter(ctx);
    Vec3 wi;
    if (!reflectAbove(o, D::sampleHalfVector(uDirection, p), &wi)) return false;
    const float pdf = pdfUpper(p, o, wi);
    if (!(pdf > 0)) return false;
    out->wi = toSideOf(wo, wi);
    out->pdf = pdf;
    out->weight = evalUpper(ctx, p, o, wi) / pdf;
    out->eta = 1;
    out->lobe = kReflection | kGlossy;
    return true;
}

template <class D>
void TorranceSparrow<D>::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(Vec3(-wo.x, -wo.y, wo.z));  // the mirror direction (two-stage §2.2)
}

template class TorranceSparrow<BlinnPhongDistribution>;
template class TorranceSparrow<BeckmannDistribution>;

}  // namespace rr
