#include "scene/materials/lambert.h"

#include "sampling/warps.h"

namespace rr {

Rgb Lambert::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return Rgb(0.0f);  // two-sided: both on the same side
    return albedo_->eval(ctx) * (kInvPi * std::abs(wi.z));
}

float Lambert::pdf(const ShadingContext&, const Vec3& wo, const Vec3& wi) const {
    if (wo.z * wi.z <= 0) return 0;
    return std::abs(wi.z) * kInvPi;
}

bool Lambert::sample(const ShadingContext& ctx, const Vec3& wo, float, Vec2 uDirection,
                     BsdfSample* out) const {
    if (wo.z == 0) return false;
    Vec3 wi = squareToCosineHemisphere(uDirection);
    if (wi.z <= 0) return false;
    if (wo.z < 0) wi.z = -wi.z;
    out->wi = wi;
    out->pdf = std::abs(wi.z) * kInvPi;
    out->weight = albedo_->eval(ctx);  // (ρ/π)·cos θ / (cos θ/π)
    out->lobe = kReflection | kDiffuse;
    return true;
}

void Lambert::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(Vec3(0, 0, wo.z < 0 ? -1.0f : 1.0f));  // the normal
}

}  // namespace rr
