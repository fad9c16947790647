#include "scene/shapes/disk.h"

#include <cmath>
#include <limits>

#include "sampling/warps.h"
#include "scene/shapes/user_geometry.h"

namespace rr {

Disk::Disk(const Vec3& center, const Vec3& normal, float radius)
    : center_(center),
      frame_(normalize(normal)),
      radius_(radius),
      errorScale_(maxAbsComponent(center) + radius) {}

RTCBounds Disk::boundsAt(float timeStep) const {
    const Vec3 c = centerAt(timeStep);
    const Vec3 n = frame_.n;
    // Extent of a disk along axis i is r·sqrt(1 − n_i²).
    const float r = radius_ * (1.0f + 1e-6f);
    const Vec3 e(r * safeSqrt(1 - n.x * n.x), r * safeSqrt(1 - n.y * n.y),
                 r * safeSqrt(1 - n.z * n.z));
    return RTCBounds{c.x - e.x, c.y - e.y, c.z - e.z, 0, c.x + e.x, c.y + e.y, c.z + e.z, 0};
}

bool Disk::hitDistance(const Vec3& origin, const Vec3& direction, float time, float tMin,
                       float tMax, float* t) const {
    const float denom = dot(direction, frame_.n);
    if (denom == 0) return false;
    const Vec3 c = center_ + offsetAt(time);
    const float tHit = dot(c - origin, frame_.n) / denom;
    if (!(tHit > tMin && tHit < tMax)) return false;
    if (lengthSquared(origin + direction * tHit - c) > radius_ * radius_) return false;
    *t = tHit;
    return true;
}

RTCGeometry Disk::createGeometry(RTCDevice device) const {
    return createUserGeometry(device, *this);
}

void Disk::completeHit(const Ray& ray, const RTCHit&, SurfaceHit* out) const {
    const Vec3 c = centerAt(ray.time);
    const Vec3 local = frame_.toLocal(ray.origin + ray.direction * out->distance - c);
    out->position = c + frame_.toWorld(Vec3(local.x, local.y, 0));  // projected onto the plane
    out->errorScale = errorScale_ + motionScale();
    out->geometricNormal = frame_.n;
    out->shadingNormal = frame_.n;
    const float phi = std::atan2(local.y, local.x);
    out->uv = Vec2(std::sqrt(local.x * local.x + local.y * local.y) / radius_,
                   (phi < 0 ? phi + kTwoPi : phi) / kTwoPi);
}

ShapeSample Disk::sampleArea(Vec2 u) const {
    const Vec2 d = squareToUniformDisk(u);
    ShapeSample s;
    s.position = center_ + frame_.toWorld(Vec3(d.x * radius_, d.y * radius_, 0));
    s.normal = frame_.n;
    s.errorScale = errorScale_;
    return s;
}

bool Disk::invertSampleDirection(const Vec3&, const Vec3& point, Vec2* u) const {
    if (hasMotion()) return false;  // the sample's position depends on the time
    const Vec3 local = frame_.toLocal(point - center_);
    *u = uniformDiskToSquare({local.x / radius_, local.y / radius_});
    return true;
}

}  // namespace rr
