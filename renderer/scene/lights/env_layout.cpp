#include "scene/lights/env_layout.h"

#include <cmath>

#include "math/sincos_pi.h"

namespace rr {

LatLongLayout::RowFactor LatLongLayout::rowFactor(float t) {
    const SinCos theta = sinCosPi(t);  // θ = πt
    return {theta.sin, theta.cos};
}

LatLongLayout::ColumnFactor LatLongLayout::columnFactor(float s) {
    const SinCos phi = sinCosPi(2 * s);  // φ = 2πs
    return {phi.sin, phi.cos};
}

bool LatLongLayout::direction(Vec2 st, Vec3* w, float* jacobian) const {
    const RowFactor row = rowFactor(st.y);
    *w = fromFactors(row, columnFactor(st.x));
    *jacobian = 2 * kPi * kPi * row.sinTheta;
    return true;
}

Vec2 LatLongLayout::imagePoint(const Vec3& w) const {
    // atan2 keeps θ accurate near the poles, where acos(y) loses precision.
    const float theta = std::atan2(std::sqrt(w.x * w.x + w.z * w.z), w.y);
    float phi = std::atan2(w.x, -w.z);
    if (phi < 0) phi += kTwoPi;
    return {phi / kTwoPi, theta / kPi};
}

float LatLongLayout::jacobian(Vec2 st) const {
    return 2 * kPi * kPi * rowFactor(st.y).sinTheta;
}

namespace {

// π sin(πρ)/ρ: the probe's dω/(du dv); π² at the centre, zero at and beyond the rim.
float probeJacobianUV(float rho) {
    if (rho >= 1) return 0;
    if (rho < 1e-6f) return kPi * kPi;
    return std::max(0.0f, kPi * (sinCosPi(rho).sin / rho));
}

}  // namespace

bool ProbeLayout::direction(Vec2 st, Vec3* w, float* jacobian) const {
    const float u = 2 * st.x - 1, v = 1 - 2 * st.y;
    const float rho = std::sqrt(u * u + v * v);
    if (rho > 1) return false;
    const SinCos theta = sinCosPi(rho);  // θ = πρ
    // sin θ / ρ → π at the centre.
    const float radial = rho > 1e-6f ? theta.sin / rho : kPi;
    *w = Vec3(-radial * u, radial * v, theta.cos);
    // probeJacobianUV(ρ) from the sine already taken (the same arithmetic, so the same value).
    *jacobian = rho < 1 ? 4 * std::max(0.0f, kPi * radial) : 0.0f;
    return true;
}

Vec2 ProbeLayout::imagePoint(const Vec3& w) const {
    const float d = std::sqrt(w.x * w.x + w.y * w.y);
    const float rho = std::atan2(d, w.z) / kPi;
    // Along ±Z the azimuth is undefined: the centre, or one point of the rim for −Z.
    const float u = d > 0 ? -w.x / d * rho : rho, v = d > 0 ? w.y / d * rho : 0.0f;
    return {(u + 1) / 2, (1 - v) / 2};
}

float ProbeLayout::jacobian(Vec2 st) const {
    const float u = 2 * st.x - 1, v = 1 - 2 * st.y;
    return 4 * probeJacobianUV(std::sqrt(u * u + v * v));
}

std::unique_ptr<EnvLayout> makeEnvLayout(const std::string& name) {
    if (name == "latlong") return std::make_unique<LatLongLayout>();
    if (name == "probe") return std::make_unique<ProbeLayout>();
    return nullptr;
}

}  // namespace rr
