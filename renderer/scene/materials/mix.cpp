#include "scene/materials/mix.h"

#include <algorithm>

namespace rr {

Rgb MixMaterial::eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const float w = weight_->eval(ctx);
    return a_->eval(ctx, wo, wi) * w + b_->eval(ctx, wo, wi) * (1.0f - w);
}

float MixMaterial::pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const {
    const float w = weight_->eval(ctx);
    return w * a_->pdf(ctx, wo, wi) + (1.0f - w) * b_->pdf(ctx, wo, wi);
}

bool MixMaterial::sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                         BsdfSample* out) const {
    const float w = weight_->eval(ctx);
    const bool chooseA = uLobe < w;
    const float probability = chooseA ? w : 1.0f - w;
    // uLobe is uniform on [0, w) or [w, 1): map each interval onto [0, 1).
    const float rescaled = chooseA ? uLobe / w : (uLobe - w) / (1.0f - w);
    const float childLobe = std::min(rescaled, kOneMinusEpsilon);  // rounding may reach 1
    if (!(chooseA ? a_ : b_)->sample(ctx, wo, childLobe, uDirection, out)) return false;
    if (out->isSpecular()) {
        out->pdf *= probability;  // (probability·value) / (probability·p): the weight stands
        return true;
    }
    out->pdf = pdf(ctx, wo, out->wi);
    if (!(out->pdf > 0)) return false;
    out->weight = eval(ctx, wo, out->wi) / out->pdf;
    return true;
}

void MixMaterial::peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const {
    peaksA_->peaks(ctx, wo, out);
    peaksB_->peaks(ctx, wo, out);
}

}  // namespace rr
