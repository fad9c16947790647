#include "scene/lights/spot_light.h"

#include <cmath>

namespace rr {

namespace {

// 1 − cos θ = 2 sin²(θ/2), accurate for narrow cones where cos θ rounds to 1.
float oneMinusCos(float angle) {
    return float(2 * std::pow(std::sin(double(angle) / 2), 2));
}

}  // namespace

SpotLight::SpotLight(const Vec3& position, const Vec3& axis, const Rgb& intensity, float cone,
                     float falloffStart)
    : position_(position),
      axis_(axis),
      intensity_(intensity),
      oneMinusCosCone_(oneMinusCos(cone)),
      oneMinusCosFalloffStart_(oneMinusCos(falloffStart)) {
    power_ = intensity * (kPi * (oneMinusCosFalloffStart_ + oneMinusCosCone_));
}

float SpotLight::falloff(const Vec3& direction) const {
    // 1 − cos θ = |w − axis|² / 2 for unit vectors: no cancellation near the axis, so the
    // penumbra of a cone of a degree or two is resolved in single precision.
    const float oneMinusCosTheta = 0.5f * lengthSquared(direction - axis_);
    if (oneMinusCosTheta <= oneMinusCosFalloffStart_) return 1;
    if (oneMinusCosTheta >= oneMinusCosCone_) return 0;
    const float x =
        (oneMinusCosCone_ - oneMinusCosTheta) / (oneMinusCosCone_ - oneMinusCosFalloffStart_);
    return x * x * (3 - 2 * x);
}

bool SpotLight::sample(const LightReference& reference, Vec2, float, LightSample* out) const {
    const Vec3 d = position_ - reference.point;
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
