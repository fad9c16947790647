#include "scene/shapes/quad.h"

namespace rr {

Quad::Quad(const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV)
    : corner_(corner), edgeU_(edgeU), edgeV_(edgeV) {
    const Vec3 n = cross(edgeU, edgeV);
    area_ = length(n);
    normal_ = n / area_;
    // Dual basis within the plane: dualU ⟂ edgeV, dot(dualU, edgeU) = 1 (and symmetrically).
    dualU_ = cross(edgeV, normal_) / dot(cross(edgeV, normal_), edgeU);
    dualV_ = cross(normal_, edgeU) / dot(cross(normal_, edgeU), edgeV);
}

RTCGeometry Quad::createGeometry(RTCDevice device) const {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
    const Vec3 vertices[4] = {corner_, corner_ + edgeU_, corner_ + edgeU_ + edgeV_,
                              corner_ + edgeV_};
    setVertexBuffers(g, vertices, 4);
    auto* index = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
    for (unsigned i = 0; i < 4; ++i)
        index[i] = i;
    rtcCommitGeometry(g);
    return g;
}

void Quad::completeHit(const Ray& ray, const RTCHit&, SurfaceHit* out) const {
    const Vec3 p = ray.origin + ray.direction * out->distance;
    const Vec3 local = p - corner_ - offsetAt(ray.time);
    out->position = p;
    out->geometricNormal = normal_;
    out->shadingNormal = normal_;
    out->uv = Vec2(clamp(dot(local, dualU_), 0, 1), clamp(dot(local, dualV_), 0, 1));
}

void Quad::sampleArea(Vec2 u, Vec3* position, Vec3* normal) const {
    *position = corner_ + edgeU_ * u.x + edgeV_ * u.y;
    *normal = normal_;
}

}  // namespace rr
