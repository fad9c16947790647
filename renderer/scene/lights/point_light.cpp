#include "scene/lights/point_light.h"

namespace rr {

bool PointLight::sample(const LightReference& reference, Vec2, float, LightSample* out) const {
    const Vec3 d = position_ - reference.point;
    const float dist2 = lengthSquared(d);
    if (dist2 == 0) return false;
    const float dist = std::sqrt(dist2);
    out->direction = d / dist;
    out->position = position_;
    out->normal = Vec3(0.0f);
    out->radiance = intensity_ / dist2;
    out->pdf = 1;
    out->isDelta = true;
    return true;
}

}  // namespace rr
