#include "scene/shapes/triangle_mesh.h"

#include <algorithm>
#include <cstring>

#include "sampling/warps.h"

namespace rr {

TriangleMesh::TriangleMesh(MeshData data) : data_(std::move(data)) {
    std::vector<float> areas(triangleCount());
    for (size_t i = 0; i < areas.size(); ++i) {
        const Vec3& a = data_.positions[data_.indices[3 * i]];
        const Vec3& b = data_.positions[data_.indices[3 * i + 1]];
        const Vec3& c = data_.positions[data_.indices[3 * i + 2]];
        areas[i] = 0.5f * length(cross(b - a, c - a));
        area_ += areas[i];
    }
    triangleByArea_ = Distribution1D(areas);
}

std::vector<Vec3> TriangleMesh::smoothNormals(const MeshData& data) {
    std::vector<Vec3> normals(data.positions.size(), Vec3(0.0f));
    for (size_t i = 0; i + 2 < data.indices.size(); i += 3) {
        const uint32_t i0 = data.indices[i], i1 = data.indices[i + 1], i2 = data.indices[i + 2];
        const Vec3 n = cross(data.positions[i1] - data.positions[i0],
                             data.positions[i2] - data.positions[i0]);  // |n| = 2·area
        normals[i0] += n;
        normals[i1] += n;
        normals[i2] += n;
    }
    for (Vec3& n : normals) {
        const float len = length(n);
        n = len > 0 ? n / len : Vec3(0, 0, 1);  // unused vertices get any unit vector
    }
    return normals;
}

RTCGeometry TriangleMesh::createGeometry(RTCDevice device) const {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    setVertexBuffers(g, data_.positions.data(), data_.positions.size());
    void* index = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                          3 * sizeof(uint32_t), triangleCount());
    std::memcpy(index, data_.indices.data(), data_.indices.size() * sizeof(uint32_t));
    rtcCommitGeometry(g);
    return g;
}

TriangleMesh::Triangle TriangleMesh::triangle(uint32_t index) const {
    const uint32_t* i = &data_.indices[3 * size_t(index)];
    return {data_.positions[i[0]], data_.positions[i[1]], data_.positions[i[2]]};
}

float TriangleMesh::Triangle::errorScale() const {
    return std::max({maxAbsComponent(p0), maxAbsComponent(p1), maxAbsComponent(p2)});
}

void TriangleMesh::completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const {
    // The hit point is interpolated from the vertices with Embree's barycentrics, so its error
    // is relative to the triangle's coordinates, not to the ray origin's distance.
    const Triangle tri = triangle(hit.primID);
    const float b0 = 1 - hit.u - hit.v;
    out->position = tri.p0 * b0 + tri.p1 * hit.u + tri.p2 * hit.v + offsetAt(ray.time);
    out->errorScale = tri.errorScale() + motionScale();
    out->geometricNormal = tri.normal();
    out->uv = Vec2(hit.u, hit.v);
    if (data_.normals.empty()) {
        out->shadingNormal = out->geometricNormal;
        return;
    }
    const uint32_t* idx = &data_.indices[3 * size_t(hit.primID)];
    Vec3 n =
        data_.normals[idx[0]] * b0 + data_.normals[idx[1]] * hit.u + data_.normals[idx[2]] * hit.v;
    const float len = length(n);
    n = len > 0 ? n / len : out->geometricNormal;
    out->shadingNormal = dot(n, out->geometricNormal) < 0 ? -n : n;
}

ShapeSample TriangleMesh::sampleArea(Vec2 u) const {
    float uRemapped;
    const int index = triangleByArea_.sample(u.x, nullptr, &uRemapped);
    const Vec2 b = squareToUniformTriangle(Vec2(uRemapped, u.y));
    const Triangle tri = triangle(static_cast<uint32_t>(index));
    ShapeSample s;
    s.position = tri.p0 * b.x + tri.p1 * b.y + tri.p2 * (1 - b.x - b.y);
    s.normal = tri.normal();
    s.errorScale = tri.errorScale();
    return s;
}

}  // namespace rr
