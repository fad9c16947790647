#include "scene/lights/constant_environment.h"

#include "sampling/warps.h"

namespace rr {

bool ConstantEnvironment::sample(const Vec3& reference, Vec2 u, float, LightSample* out) const {
    out->direction = squareToUniformSphere(u);
    // Twice the diameter: outside the bounding sphere from any point inside it.
    out->position = reference + out->direction * (4.0f * radius_);
    out->normal = Vec3(0.0f);
    out->errorScale = 0;
    out->radiance = radiance_;
    out->pdf = uniformSpherePdf();
    out->isDelta = false;
    return !radiance_.isBlack();
}

float ConstantEnvironment::directionPdf(const Vec3&) const {
    return uniformSpherePdf();
}

bool ConstantEnvironment::invertSample(const Vec3&, const Vec3& direction, const Vec3&,
                                       Vec2* u) const {
    *u = uniformSphereToSquare(direction);
    return true;
}

}  // namespace rr
