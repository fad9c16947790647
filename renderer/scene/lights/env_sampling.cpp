#include "scene/lights/env_sampling.h"

#include <algorithm>
#include <cmath>

#include "math/frame.h"
#include "sampling/warps.h"

namespace rr {
namespace {

bool hasNormal(const LightReference& reference) {
    return lengthSquared(reference.normal) > 0;
}

// Cosine about the normal needs one; without it pbrt-v1 falls back to the uniform sphere.
bool cosineAboutNormal(EnvSampling how, const LightReference& reference) {
    return how == EnvSampling::Cosine && hasNormal(reference);
}

}  // namespace

bool sampleEnvDirection(EnvSampling how, const LightReference& reference, Vec2 u, Vec3* w,
                        float* pdf) {
    if (!cosineAboutNormal(how, reference)) {
        *w = squareToUniformSphere(u);
        *pdf = uniformSpherePdf();
        return true;
    }
    // u.x's lower half picks the normal's side, its upper half the other, each rescaled to
    // [0, 1) for the cosine-weighted hemisphere (pbrt-v1 flips z with a separate random number).
    const bool below = u.x >= 0.5f;
    u.x = below ? 2 * u.x - 1 : 2 * u.x;
    Vec3 local = squareToCosineHemisphere(clampToUnitSquare(u));
    if (below) local.z = -local.z;
    *w = normalize(Frame(reference.normal).toWorld(local));
    *pdf = envDirectionPdf(how, reference, *w);
    return *pdf > 0;
}

float envDirectionPdf(EnvSampling how, const LightReference& reference, const Vec3& w) {
    if (!cosineAboutNormal(how, reference)) return uniformSpherePdf();
    return std::abs(dot(reference.normal, w)) * (0.5f * kInvPi);
}

bool invertEnvDirection(EnvSampling how, const LightReference& reference, const Vec3& w, Vec2* u) {
    if (!cosineAboutNormal(how, reference)) {
        *u = uniformSphereToSquare(w);
        return true;
    }
    const Vec3 local = Frame(reference.normal).toLocal(w);
    if (local.z == 0) return false;
    // squareToCosineHemisphere projects a uniform disc point up: the disc point is (x, y).
    const Vec2 square = uniformDiskToSquare(Vec2(local.x, local.y));
    const bool below = local.z < 0;
    // 0.5 + 0.5·x rounds up to 1 for x just below 1: keep u in [0, 1).
    *u = Vec2(below ? std::min(0.5f + 0.5f * square.x, kOneMinusEpsilon) : 0.5f * square.x,
              square.y);
    return true;
}

}  // namespace rr
