#include "scene/materials/phong.h"

#include "sampling/warps.h"
#include "scene/materials/cosine_lobe.h"

namespace rr {

namespace {

Vec3 mirrorDirection(const Vec3& wo) {
    return Vec3(-wo.x, -wo.y, wo.z);
}

}  // namespace

float Phong::diffuseProbability(const Rgb& kd, const Rgb& ks) {
    const float total = kd.luminance() + ks.luminance();
    return total > 0 ? kd.luminance() / total : -1.0f;
}

Rgb Phong::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);  // two-sided: both on the same side
    const double n = exponent_->eval(ctx);
    const double lobe =
        (n + 2) / (2 * M_PI) * cosinePower(oneMinusCosine(wi, mirrorDirection(wo)), n);
    const Rgb f = diffuse_->eval(ctx) * kInvPi + specular_->eval(ctx) * float(lobe);
    return f * std::abs(wi.z);
}

float Phong::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    const float pd = diffuseProbability(diffuse_->eval(ctx), specular_->eval(ctx));
    if (pd < 0) return 0;
    const double n = exponent_->eval(ctx);
    const double lobe = cosinePowerPdf(oneMinusCosine(wi, mirrorDirection(wo)), n);
    return float(pd * std::abs(wi.z) * kInvPi + (1 - pd) * lobe);
}

bool Phong::sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                   BsdfSample* out) const {
    if (wo.z == 0) return false;
    const float pd = diffuseProbability(diffuse_->eval(ctx), specular_->eval(ctx));
    if (pd < 0) return false;  // black
    Vec3 wi;
    if (uLobe < pd) {
        wi = squareToCosineHemisphere(uDirection);
        if (wo.z < 0) wi.z = -wi.z;
    } else {
        wi = sampleCosinePower(uDirection, exponent_->eval(ctx), mirrorDirection(wo));
    }
    if (wi.z * wo.z <= 0) return false;  // the lobe's part below the surface, or the horizon
    out->wi = wi;
    out->pdf = pdf(ctx, wo, wi);
    if (!(out->pdf > 0)) return false;  // a lobe direction whose density underflowed
    out->weight = eval(ctx, wo, wi) / out->pdf;
    out->lobe = kReflection | (uLobe < pd ? kDiffuse : kGlossy);
    return true;
}

void Phong::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(mirrorDirection(wo));
}

}  // namespace rr
