#include "scene/shapes/sphere.h"

#include <cmath>

#include "sampling/warps.h"
#include "scene/shapes/user_geometry.h"

namespace rr {

RTCBounds Sphere::boundsAt(float timeStep) const {
    const Vec3 c = centerAt(timeStep);
    const float r = radius_ * (1.0f + 1e-6f);
    return RTCBounds{c.x - r, c.y - r, c.z - r, 0, c.x + r, c.y + r, c.z + r, 0};
}

Vec3 Sphere::hitNormal(const Vec3& origin, const Vec3& direction, float time, float t) const {
    return origin + direction * t - centerAt(time);
}

bool Sphere::hitDistance(const Vec3& origin, const Vec3& direction, float time, float tMin,
                         float tMax, float* t) const {
    const Vec3 center = centerAt(time);
    const double ox = double(origin.x) - center.x, oy = double(origin.y) - center.y,
                 oz = double(origin.z) - center.z;
    const double dx = direction.x, dy = direction.y, dz = direction.z;
    const double a = dx * dx + dy * dy + dz * dz;
    const double b = ox * dx + oy * dy + oz * dz;  // half of the linear coefficient
    // c − b²/a computed as |o − (b/a) d|² − r² avoids cancellation for distant spheres.
    const double px = ox - b / a * dx, py = oy - b / a * dy, pz = oz - b / a * dz;
    const double r = radius_;
    const double discriminant = a * (r * r - (px * px + py * py + pz * pz));
    if (discriminant < 0) return false;
    const double q = -b - std::copysign(std::sqrt(discriminant), b);
    const double c = ox * ox + oy * oy + oz * oz - r * r;
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tMin && t0 < tMax) {
        *t = static_cast<float>(t0);
        return true;
    }
    if (t1 > tMin && t1 < tMax) {
        *t = static_cast<float>(t1);
        return true;
    }
    return false;
}

RTCGeometry Sphere::createGeometry(RTCDevice device) const {
    return createUserGeometry(device, *this);
}

void Sphere::completeHit(const Ray& ray, const RTCHit&, SurfaceHit* out) const {
    const Vec3 c = centerAt(ray.time);
    const Vec3 n = normalize(ray.origin + ray.direction * out->distance - c);
    out->position = c + n * radius_;  // reprojected onto the surface: exact up to rounding
    out->errorScale = errorScale_ + motionScale();
    out->geometricNormal = n;
    out->shadingNormal = n;
    const Vec3 local = orientation_.toLocal(n);
    const float phi = std::atan2(local.y, local.x);
    out->uv = Vec2((phi < 0 ? phi + kTwoPi : phi) / kTwoPi, safeAcos(local.z) * kInvPi);
    // ∂p/∂φ: along the parallels (zero at the poles).
    out->tangent = orientation_.toWorld(Vec3(-local.y, local.x, 0));
}

ShapeSample Sphere::sampleArea(Vec2 u) const {
    ShapeSample s;
    s.normal = squareToUniformSphere(u);
    s.position = center_ + s.normal * radius_;
    s.errorScale = errorScale_;
    return s;
}

bool Sphere::sampleDirection(const Vec3& reference, Vec2 u, float time, ShapeSample* out) const {
    const Vec3 c = centerAt(time);
    const Vec3 toCenter = c - reference;
    const float dist2 = lengthSquared(toCenter);
    const float r2 = radius_ * radius_;
    if (!samplesCone(dist2)) return Shape::sampleDirection(reference, u, time, out);

    // Uniform directions in the cone the sphere subtends; then the nearest intersection.
    const float dist = std::sqrt(dist2);
    const float oneMinusCosMax = coneOneMinusCos(r2 / dist2);
    const Frame frame(toCenter / dist);
    const Vec3 w = frame.toWorld(squareToUniformCone(u, oneMinusCosMax));
    float t;
    Vec3 n;
    if (hitDistance(reference, w, time, 0.0f, std::numeric_limits<float>::infinity(), &t)) {
        n = normalize(reference + w * t - c);
    } else {
        // Grazing direction lost to rounding: take the tangent point (the ray's closest
        // approach), moved back along the ray by 1e-3·r so that it faces the reference: at the
        // exact tangent point the cosine is zero with a rounding-noise sign, and AreaLight
        // dropped the sample as back-facing about half the time.
        n = normalize(normalize(reference + w * dot(toCenter, w) - c) - w * 1e-3f);
    }
    out->position = c + n * radius_;
    out->normal = n;
    out->pdf = uniformConePdf(oneMinusCosMax);
    out->errorScale = errorScale_ + motionScale();
    return true;
}

float Sphere::directionPdf(const Vec3& reference, const SurfaceHit& hit) const {
    const Vec3 c = centerAt(hit.time);
    const float dist2 = lengthSquared(c - reference);
    if (!samplesCone(dist2)) return Shape::directionPdf(reference, hit);
    return uniformConePdf(coneOneMinusCos(radius_ * radius_ / dist2));
}

bool Sphere::invertSampleDirection(const Vec3& reference, const Vec3& point, Vec2* u) const {
    if (hasMotion()) return false;  // the cone and the sphere's points depend on the time
    const Vec3 toCenter = center_ - reference;
    const float dist2 = lengthSquared(toCenter);
    if (!samplesCone(dist2)) {
        // Shape::sampleDirection: sampleArea's normal is squareToUniformSphere(u).
        *u = uniformSphereToSquare(normalize(point - center_));
        return true;
    }
    const Vec3 d = point - reference;
    const float dist = length(d);
    if (!(dist > 0)) return false;
    // The same cone and frame as sampleDirection.
    const Frame frame(toCenter / std::sqrt(dist2));
    *u = uniformConeToSquare(frame.toLocal(d / dist), coneOneMinusCos(radius_ * radius_ / dist2));
    return true;
}

}  // namespace rr
