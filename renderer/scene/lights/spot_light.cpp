#include "scene/lights/spot_light.h"

#include <cmath>

namespace rr {

SpotLight::SpotLight(const Vec3& position, const Vec3& axis, const Rgb& intensity, float cone,
                     float falloffStart)
    : position_(position),
      axis_(axis),
      intensity_(intensity),
      cosCone_(std::cos(cone)),
      cosFalloffStart_(std::cos(falloffStart)) {
    // 1 − cos θ = 2 sin²(θ/2), accurate for narrow cones where cos θ rounds to 1.
    const auto oneMinusCos = [](double angle) { return 2 * std::pow(std::sin(angle / 2), 2); };
    power_ = intensity * float(kPi * (oneMinusCos(falloffStart) + oneMinusCos(cone)));
}

float SpotLight::falloff(const Vec3& direction) const {
    const float cosTheta = dot(direction, axis_);
    if (cosTheta >= cosFalloffStart_) return 1;
    if (cosTheta <= cosCone_) return 0;
    const float x = (cosTheta - cosCone_) / (cosFalloffStart_ - cosCone_);
    return x * x * (3 - 2 * x);
}

bool SpotLight::sample(const Vec3& reference, Vec2, float, LightSample* out) const {
    const Vec3 d = position_ - reference;
    const float dist2 = lengthSquared(d);
    if (dist2 == 0) return false;
    const float dist = std::sqrt(dist2);
    out->direction = d / dist;
    const float f = falloff(-out->direction);
    if (f == 0) return false;
    out->position = position_;
    out->normal = Vec3(0.0f);
    out->errorScale = 0;
    out->radiance = intensity_ * (f / dist2);
    out->pdf = 1;
    out->isDelta = true;
    return true;
}

}  // namespace rr
