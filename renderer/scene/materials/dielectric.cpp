#include "scene/materials/dielectric.h"

#include <cmath>

namespace rr {

float fresnelDielectric(float cosThetaI, float eta) {
    if (cosThetaI < 0) {  // leaving the interior
        eta = 1.0f / eta;
        cosThetaI = -cosThetaI;
    }
    const float sin2ThetaT = (1.0f - cosThetaI * cosThetaI) / (eta * eta);
    if (sin2ThetaT >= 1.0f) return 1.0f;  // total internal reflection
    const float cosThetaT = safeSqrt(1.0f - sin2ThetaT);
    const float rParallel = (eta * cosThetaI - cosThetaT) / (eta * cosThetaI + cosThetaT);
    const float rPerpendicular = (cosThetaI - eta * cosThetaT) / (cosThetaI + eta * cosThetaT);
    return 0.5f * (rParallel * rParallel + rPerpendicular * rPerpendicular);
}

bool Dielectric::refract(const Vec3& wo, Vec3* wt, float* etaRelative) const {
    const bool entering = wo.z > 0;
    const float eta = entering ? eta_ : 1.0f / eta_;  // ηt / ηi
    const float cosI = std::abs(wo.z);
    const float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) return false;
    const float cosT = safeSqrt(1.0f - sin2T);
    *wt = Vec3(-wo.x / eta, -wo.y / eta, entering ? -cosT : cosT);
    *etaRelative = eta;
    return true;
}

bool Dielectric::sample(const ShadingContext&, const Vec3& wo, float uLobe, Vec2,
                        BsdfSample* out) const {
    if (wo.z == 0) return false;
    const float f = reflectProbability(wo);
    if (uLobe < f) {
        out->wi = Vec3(-wo.x, -wo.y, wo.z);
        out->pdf = f;
        out->eta = 1;
        out->weight = reflectance_;  // (F·R) / F
        out->lobe = kReflection | kSpecular;
        return true;
    }
    float eta;
    if (!refract(wo, &out->wi, &eta)) return false;  // unreachable: F = 1 under TIR
    out->pdf = 1.0f - f;
    out->eta = eta;
    out->weight = transmittance_ * (1.0f / (eta * eta));  // ((1−F)·T/η²) / (1−F)
    out->lobe = kTransmission | kSpecular;
    return true;
}

void Dielectric::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(Vec3(-wo.x, -wo.y, wo.z));
    Vec3 wt;
    float eta;
    if (refract(wo, &wt, &eta)) out->add(wt);
}

}  // namespace rr
