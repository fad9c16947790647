// Embree user geometry for the shapes that are intersected analytically (sphere, disk): one
// primitive whose bounds, intersection and occlusion callbacks ask the shape. `S` provides
//   RTCBounds boundsAt(float timeStep) const;  // at Embree's time step 0 or 1
//   bool hitDistance(const Vec3& origin, const Vec3& direction, float time, float tMin,
//                    float tMax, float* t) const;  // nearest t in (tMin, tMax)
//   Vec3 hitNormal(const Vec3& origin, const Vec3& direction, float time, float t) const;
// The callbacks are templates on S so that the shape's test is inlined into them.
#pragma once

#include <embree3/rtcore.h>

#include <limits>

#include "math/vector.h"

namespace rr {

namespace user_geometry {

inline Vec3 rayOrigin(RTCRayN* rays, unsigned n, unsigned i) {
    return {RTCRayN_org_x(rays, n, i), RTCRayN_org_y(rays, n, i), RTCRayN_org_z(rays, n, i)};
}
inline Vec3 rayDirection(RTCRayN* rays, unsigned n, unsigned i) {
    return {RTCRayN_dir_x(rays, n, i), RTCRayN_dir_y(rays, n, i), RTCRayN_dir_z(rays, n, i)};
}

template <class S>
bool hitDistance(const S& shape, RTCRayN* rays, unsigned n, unsigned i, float* t) {
    return shape.hitDistance(rayOrigin(rays, n, i), rayDirection(rays, n, i),
                             RTCRayN_time(rays, n, i), RTCRayN_tnear(rays, n, i),
                             RTCRayN_tfar(rays, n, i), t);
}

template <class S>
void bounds(const RTCBoundsFunctionArguments* args) {
    const auto* shape = static_cast<const S*>(args->geometryUserPtr);
    *args->bounds_o = shape->boundsAt(static_cast<float>(args->timeStep));
}

template <class S>
void intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* shape = static_cast<const S*>(args->geometryUserPtr);
    RTCRayN* rays = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hits = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        float t;
        if (args->valid[i] == 0 || !hitDistance(*shape, rays, args->N, i, &t)) continue;
        RTCRayN_tfar(rays, args->N, i) = t;
        const Vec3 n = shape->hitNormal(rayOrigin(rays, args->N, i), rayDirection(rays, args->N, i),
                                        RTCRayN_time(rays, args->N, i), t);
        RTCHitN_Ng_x(hits, args->N, i) = n.x;
        RTCHitN_Ng_y(hits, args->N, i) = n.y;
        RTCHitN_Ng_z(hits, args->N, i) = n.z;
        RTCHitN_u(hits, args->N, i) = 0;
        RTCHitN_v(hits, args->N, i) = 0;
        RTCHitN_primID(hits, args->N, i) = args->primID;
        RTCHitN_geomID(hits, args->N, i) = args->geomID;
        RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
    }
}

template <class S>
void occluded(const RTCOccludedFunctionNArguments* args) {
    const auto* shape = static_cast<const S*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        float t;
        if (args->valid[i] != 0 && hitDistance(*shape, args->ray, args->N, i, &t))
            RTCRayN_tfar(args->ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
}

}  // namespace user_geometry

// The committed geometry of `shape`, with two time steps when it moves.
template <class S>
RTCGeometry createUserGeometry(RTCDevice device, const S& shape) {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, 1);
    rtcSetGeometryTimeStepCount(g, shape.hasMotion() ? 2 : 1);
    rtcSetGeometryUserData(g, const_cast<S*>(&shape));
    rtcSetGeometryBoundsFunction(g, user_geometry::bounds<S>, nullptr);
    rtcSetGeometryIntersectFunction(g, user_geometry::intersect<S>);
    rtcSetGeometryOccludedFunction(g, user_geometry::occluded<S>);
    rtcCommitGeometry(g);
    return g;
}

}  // namespace rr
