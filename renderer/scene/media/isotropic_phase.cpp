#include "scene/media/isotropic_phase.h"

#include "sampling/warps.h"

namespace rr {

float IsotropicPhase::eval(const Vec3&, const Vec3&) const {
    return uniformSpherePdf();
}

float IsotropicPhase::pdf(const Vec3&, const Vec3&) const {
    return uniformSpherePdf();
}

float IsotropicPhase::sample(const Vec3&, Vec2 u, Vec3* wi) const {
    *wi = squareToUniformSphere(u);
    return uniformSpherePdf();
}

}  // namespace rr
