#include "scene/materials/mirror.h"

namespace rr {

bool Mirror::sample(const ShadingContext&, const Vec3& wo, float, Vec2, BsdfSample* out) const {
    if (wo.z == 0) return false;
    out->wi = Vec3(-wo.x, -wo.y, wo.z);
    out->pdf = 1;
    out->weight = reflectance_;
    out->lobe = kReflection | kSpecular;
    return true;
}

void Mirror::peaks(const ShadingContext&, const Vec3& wo, LobePeaks* out) const {
    out->add(Vec3(-wo.x, -wo.y, wo.z));
}

}  // namespace rr
