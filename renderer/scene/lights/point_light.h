// Isotropic point light of radiant intensity I (W/sr): irradiance I·cos θ / d².
#pragma once

#include "scene/light.h"

namespace rr {

class PointLight final : public Light {
  public:
    PointLight(const Vec3& position, const Rgb& intensity)
        : position_(position), intensity_(intensity) {}

    bool sample(const LightReference& reference, Vec2 u, float time,
                LightSample* out) const override;
    float pdf(const Vec3&, const SurfaceHit&) const override { return 0; }
    Rgb power() const override { return intensity_ * (4.0f * kPi); }
    bool isDelta() const override { return true; }

  private:
    Vec3 position_;
    Rgb intensity_;
};

}  // namespace rr
