#include "scene/materials/phong.h"

#include "sampling/warps.h"
#include "scene/materials/cosine_lobe.h"

namespace rr {

namespace {

Vec3 mirrorDirection(const Vec3& wo) {
    return Vec3(-wo.x, -wo.y, wo.z);
}

}  // namespace

Phong::Parameters Phong::at(const ShadingContext& ctx) const {
    Parameters p{diffuse_->eval(ctx), specular_->eval(ctx), exponent_->eval(ctx), -1.0f};
    const float total = p.kd.luminance() + p.ks.luminance();
    if (total > 0) p.diffuseProbability = p.kd.luminance() / total;
    return p;
}

Rgb Phong::evalWith(const Parameters& p, const Vec3& wo, const Vec3& wi) {
    const double lobe =
        (p.n + 2) / (2 * M_PI) * cosinePower(oneMinusCosine(wi, mirrorDirection(wo)), p.n);
    return (p.kd * kInvPi + p.ks * float(lobe)) * std::abs(wi.z);
}

float Phong::pdfWith(const Parameters& p, const Vec3& wo, const Vec3& wi) {
    if (p.diffuseProbability < 0) return 0;
    const double lobe = cosinePowerPdf(oneMinusCosine(wi, mirrorDirection(wo)), p.n);
    const float pd = p.diffuseProbability;
    return float(pd * std::abs(wi.z) * kInvPi + (1 - pd) * lobe);
}

Rgb Phong::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);  // two-sided: both on the same side
    return evalWith(at(ctx), wo, wi);
}

float Phong::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return pdfWith(at(ctx), wo, wi);
}

bool Phong::sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                   BsdfSample* out) const {
    if (wo.z == 0) return false;
    const Parameters p = at(ctx);
    if (p.diffuseProbability < 0) return false;  // black
    const bool diffuse = uLobe < p.diffuseProbability;
    Vec3 wi;
    if (diffuse) {
        wi = squareToCosineHemisphere(uDirection);
        if (wo.z < 0) wi.z = -wi.z;
    } else {
        wi = sampleCosinePower(uDirection, p.n, mirrorDirection(wo));
    }
    if (wi.z * wo.z <= 0) return false;  // the lobe's part below the surface, or the horizon
    out->wi = wi;
    out->pdf = pdfWith(p, wo, wi);
    if (!(out->pdf > 0)) return false;  // a lobe direction whose density underflowed
    out->weight = evalWith(p, wo, wi) / out->pdf;
    out->lobe = kReflection | (diffuse ? kDiffuse : kGlossy);
    return true;
}

void Phong::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(mirrorDirection(wo));
}

}  // namespace rr
