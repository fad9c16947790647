#include "scene/lights/area_light.h"

#include <cmath>

namespace rr {

bool AreaLight::sample(const LightReference& reference, Vec2 u, float time,
                       LightSample* out) const {
    ShapeSample s;
    if (!shape_->sampleDirection(reference.point, u, time, &s)) return false;
    const Vec3 d = s.position - reference.point;
    const float dist = length(d);
    if (dist == 0) return false;
    out->direction = d / dist;
    out->position = s.position;
    out->normal = s.normal;
    out->errorScale = s.errorScale;
    out->radiance = emitted(s.normal, -out->direction);
    out->pdf = s.pdf;
    out->isDelta = false;
    return !out->radiance.isBlack() && s.pdf > 0;
}

float AreaLight::pdf(const Vec3& reference, const SurfaceHit& hit) const {
    return shape_->directionPdf(reference, hit);
}

bool AreaLight::invertSample(const LightReference& reference, const Vec3&, const Vec3& point,
                             Vec2* u) const {
    return shape_->invertSampleDirection(reference.point, point, u);
}

Rgb AreaLight::power() const {
    return radiance_ * (kPi * shape_->area() * (twoSided_ ? 2.0f : 1.0f));
}

}  // namespace rr
