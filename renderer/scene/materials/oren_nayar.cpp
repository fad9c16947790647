#include "scene/materials/oren_nayar.h"

#include "sampling/warps.h"

namespace rr {

Rgb OrenNayar::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);  // two-sided: both on the same side
    const float sigma = sigmaDegrees_->eval(ctx) * (kPi / 180.0f);
    const float sigma2 = sigma * sigma;
    const float a = 1.0f - 0.5f * sigma2 / (sigma2 + 0.33f);
    const float b = 0.45f * sigma2 / (sigma2 + 0.09f);
    // cos(φi − φo)·sin α·tan β without trigonometry: with sin θ·cos φ = w.x, sin θ·sin φ = w.y,
    // cos(φi − φo)·sin θi·sin θo is the dot product of the tangential parts, and sin α·tan β
    // = sin θi·sin θo / cos β, β being the angle with the larger cosine.
    const float cosI = std::abs(wi.z), cosO = std::abs(wo.z);
    const float tangential = std::max(0.0f, wi.x * wo.x + wi.y * wo.y);
    const float shape = a + b * tangential / std::max(cosI, cosO);
    return albedo_->eval(ctx) * (kInvPi * shape * cosI);
}

float OrenNayar::pdf(const ShadingContext&, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return std::abs(wi.z) * kInvPi;
}

bool OrenNayar::sample(const ShadingContext& ctx, const Vec3& wo, float, Vec2 uDirection,
                       BsdfSample* out) const {
    if (wo.z == 0) return false;
    Vec3 wi = squareToCosineHemisphere(uDirection);
    if (wi.z <= 0) return false;  // on the rim of the disk: the horizon, where the pdf is 0
    if (wo.z < 0) wi.z = -wi.z;
    out->wi = wi;
    out->pdf = pdf(ctx, wo, wi);
    out->weight = eval(ctx, wo, wi) / out->pdf;
    out->lobe = kReflection | kDiffuse;
    return true;
}

void OrenNayar::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(wo);                                   // retro-reflection
    out->add(Vec3(0, 0, wo.z < 0 ? -1.0f : 1.0f));  // the normal
}

}  // namespace rr
