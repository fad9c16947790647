// Perfect specular reflection with a constant reflectance.
#pragma once

#include "scene/lobe_peaks.h"

namespace rr {

class Mirror final : public Material, public LobePeakSource {
  public:
    explicit Mirror(const Rgb& reflectance) : reflectance_(reflectance) {}

    Rgb eval(const ShadingContext&, const Vec3&, const Vec3&) const override { return Rgb(0.0f); }
    float pdf(const ShadingContext&, const Vec3&, const Vec3&) const override { return 0; }
    bool sample(const ShadingContext&, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override;
    void peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const override;
    uint8_t lobes() const override { return kReflection | kSpecular; }

  private:
    Rgb reflectance_;
};

}  // namespace rr
