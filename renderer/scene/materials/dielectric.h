// Smooth dielectric interface (glass): Fresnel-weighted choice between specular reflection and
// refraction. The choice is the BsdfLobe decision: reflect when uLobe < F. Radiance crossing
// the interface is scaled by 1/η² (η = ηt/ηi), as for camera paths (Veach 1997, §5.2).
#pragma once

#include "scene/lobe_peaks.h"

namespace rr {

// Unpolarised Fresnel reflectance of a dielectric interface; cosThetaI may be negative
// (coming from inside). `eta` is interior IOR / exterior IOR.
float fresnelDielectric(float cosThetaI, float eta);

class Dielectric final : public Material, public LobePeakSource {
  public:
    Dielectric(float eta, const Rgb& reflectance, const Rgb& transmittance)
        : eta_(eta), reflectance_(reflectance), transmittance_(transmittance) {}

    Rgb eval(const ShadingContext&, const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
    float pdf(const ShadingContext&, const Vec3&, const Vec3&) const override { return 0; }
    bool sample(const ShadingContext&, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kTransmission | kSpecular; }

    // Probability that sample() reflects (= Fresnel reflectance for wo).
    float reflectProbability(const Vec3& wo) const { return fresnelDielectric(wo.z, eta_); }
    float reflectionChoice(const ShadingContext&, const Vec3& wo) const override {
        return reflectProbability(wo);
    }

  private:
    bool refract(const Vec3& wo, Vec3* wt, float* etaRelative) const;

    float eta_;
    Rgb reflectance_, transmittance_;
};

}  // namespace rr
