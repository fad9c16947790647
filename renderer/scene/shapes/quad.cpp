#include "scene/shapes/quad.h"

#include <algorithm>

#include "sampling/warps.h"

namespace rr {

Quad::Quad(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV)
    : corner_(corner), edgeU_(edgeU), edgeV_(edgeV) {
    const Vec3 n = cross(edgeU, edgeV);
    area_ = length(n);
    normal_ = n / area_;
    // Dual basis within the plane: dualU ⟂ edgeV, dot(dualU, edgeU) = 1 (and symmetrically).
    dualU_ = cross(edgeV, normal_) / dot(cross(edgeV, normal_), edgeU);
    dualV_ = cross(normal_, edgeU) / dot(cross(normal_, edgeU), edgeV);
    errorScale_ = maxAbsComponent(corner) + maxAbsComponent(edgeU) + maxAbsComponent(edgeV);
}

// Two triangles rather than an Embree quad: Embree keeps one BVH per primitive type, so a quad
// beside a triangle mesh (a ground under the dragon) made every ray traverse two hierarchies.
// completeHit recomputes the hit from the ray either way.
RTCGeometry Quad::createGeometry(RTCDevice device) const {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    const Vec3 vertices[4] = {corner_, corner_ + edgeU_, corner_ + edgeU_ + edgeV_,
                              corner_ + edgeV_};
    setVertexBuffers(g, vertices, 4);
    auto* index = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), 2));
    const unsigned corners[6] = {0, 1, 3, 2, 3, 1};
    std::copy(corners, corners + 6, index);
    rtcCommitGeometry(g);
    return g;
}

void Quad::completeHit(const Ray& ray, const RTCHit&, SurfaceHit* out) const {
    // The hit is recomputed from its (s, t): its error is then relative to the quad's own
    // coordinates, not to the ray origin's distance.
    const Vec3 corner = corner_ + offsetAt(ray.time);
    const Vec3 local = ray.origin + ray.direction * out->distance - corner;
    out->uv = Vec2(clamp(dot(local, dualU_), 0, 1), clamp(dot(local, dualV_), 0, 1));
    out->position = corner + edgeU_ * out->uv.x + edgeV_ * out->uv.y;
    out->errorScale = errorScale_ + motionScale();
    out->geometricNormal = normal_;
    out->shadingNormal = normal_;
    out->tangent = edgeU_;
}

ShapeSample Quad::sampleArea(Vec2 u) const {
    ShapeSample s;
    s.position = corner_ + edgeU_ * u.x + edgeV_ * u.y;
    s.normal = normal_;
    s.errorScale = errorScale_;
    return s;
}

bool Quad::invertSampleDirection(const Vec3&, const Vec3& point, Vec2* u) const {
    if (hasMotion()) return false;  // the sample's position depends on the time
    const Vec3 local = point - corner_;
    *u = clampToUnitSquare({dot(local, dualU_), dot(local, dualV_)});
    return true;
}

}  // namespace rr
