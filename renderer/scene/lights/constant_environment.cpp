#include "scene/lights/constant_environment.h"

namespace rr {

bool ConstantEnvironment::sample(const LightReference& reference, Vec2 u, float,
                                 LightSample* out) const {
    if (!sampleEnvDirection(sampling_, reference, u, &out->direction, &out->pdf)) return false;
    // Twice the diameter: outside the bounding sphere from any point inside it.
    out->position = reference.point + out->direction * (4.0f * radius_);
    out->normal = Vec3(0.0f);
    out->errorScale = 0;
    out->radiance = radiance_;
    out->isDelta = false;
    return !radiance_.isBlack();
}

float ConstantEnvironment::directionPdf(const LightReference& reference, const Vec3& w) const {
    return envDirectionPdf(sampling_, reference, w);
}

bool ConstantEnvironment::invertSample(const LightReference& reference, const Vec3& direction,
                                       const Vec3&, Vec2* u) const {
    return invertEnvDirection(sampling_, reference, direction, u);
}

}  // namespace rr
