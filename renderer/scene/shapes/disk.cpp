#include "scene/shapes/disk.h"

#include <cmath>
#include <limits>

#include "sampling/warps.h"

namespace rr {

namespace {

void diskBounds(const RTCBoundsFunctionArguments* args) {
    const auto* d = static_cast<const Disk*>(args->geometryUserPtr);
    const Vec3 c = d->centerAt(static_cast<float>(args->timeStep));
    const Vec3 n = d->normal();
    // Extent of a disk along axis i is r·sqrt(1 − n_i²).
    const float r = d->radius() * (1.0f + 1e-6f);
    const Vec3 e(r * safeSqrt(1 - n.x * n.x), r * safeSqrt(1 - n.y * n.y),
                 r * safeSqrt(1 - n.z * n.z));
    *args->bounds_o =
        RTCBounds{c.x - e.x, c.y - e.y, c.z - e.z, 0, c.x + e.x, c.y + e.y, c.z + e.z, 0};
}

bool diskHit(const Disk* d, RTCRayN* rays, unsigned n, unsigned i, float* t) {
    const Vec3 o(RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i));
    const Vec3 dir(RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i));
    return d->intersect(o, dir, d->offsetAt(RTCRayN_time(rays, n, i)), RTCRayN_tnear(rays, n, i),
                        RTCRayN_tfar(rays, n, i), t);
}

void diskIntersect(const RTCIntersectFunctionNArguments* args) {
    const auto* d = static_cast<const Disk*>(args->geometryUserPtr);
    RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        float t;
        if (args->valid[i] == 0 || !diskHit(d, rays, args->N, i, &t)) continue;
        RTCRayN_tfar(rays, args->N, i) = t;
        RTCHitN_Ng_x(hits, args->N, i) = d->normal().x;
        RTCHitN_Ng_y(hits, args->N, i) = d->normal().y;
        RTCHitN_Ng_z(hits, args->N, i) = d->normal().z;
        RTCHitN_u(hits, args->N, i) = 0;
        RTCHitN_v(hits, args->N, i) = 0;
        RTCHitN_primID(hits, args->N, i) = args->primID;
        RTCHitN_geomID(hits, args->N, i) = args->geomID;
        RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
    }
}

void diskOccluded(const RTCOccludedFunctionNArguments* args) {
    const auto* d = static_cast<const Disk*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        float t;
        if (args->valid[i] != 0 && diskHit(d, args->ray, args->N, i, &t))
            RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
}

}  // namespace

Disk::Disk(const Vec3& center, const Vec3& normal, float radius)
    : center_(center),
      frame_(normalize(normal)),
      radius_(radius),
      errorScale_(maxAbsComponent(center) + radius) {}

bool Disk::intersect(const Vec3& origin, const Vec3& direction, const Vec3& offset, float tMin,
                     float tMax, float* t) const {
    const float denom = dot(direction, frame_.n);
    if (denom == 0) return false;
    const Vec3 c = center_ + offset;
    const float tHit = dot(c - origin, frame_.n) / denom;
    if (!(tHit > tMin && tHit < tMax)) return false;
    if (lengthSquared(origin + direction * tHit - c) > radius_ * radius_) return false;
    *t = tHit;
    return true;
}

RTCGeometry Disk::createGeometry(RTCDevice device) const {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryTimeStepCount(g, hasMotion() ? 2 : 1);
    rtcSetGeometryUserData(g, const_cast<Disk*>(this));
    rtcSetGeometryBoundsFunction(g, diskBounds, nullptr);
    rtcSetGeometryIntersectFunction(g, diskIntersect);
    rtcSetGeometryOccludedFunction(g, diskOccluded);
    rtcCommitGeometry(g);
    return g;
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
