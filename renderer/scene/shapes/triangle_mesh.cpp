#include "scene/shapes/triangle_mesh.h"

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

Vec3 TriangleMesh::faceNormal(uint32_t triangle) const {
    const Vec3& a = data_.positions[data_.indices[3 * triangle]];
    const Vec3& b = data_.positions[data_.indices[3 * triangle + 1]];
    const Vec3& c = data_.positions[data_.indices[3 * triangle + 2]];
    return normalize(cross(b - a, c - a));
}

void TriangleMesh::completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const {
    out->position = ray.origin + ray.direction * out->distance;
    out->geometricNormal = faceNormal(hit.primID);
    out->uv = Vec2(hit.u, hit.v);
    if (data_.normals.empty()) {
        out->shadingNormal = out->geometricNormal;
        return;
    }
    const uint32_t* idx = &data_.indices[3 * hit.primID];
    Vec3 n = data_.normals[idx[0]] * (1 - hit.u - hit.v) + data_.normals[idx[1]] * hit.u +
             data_.normals[idx[2]] * hit.v;
    const float len = length(n);
    n = len > 0 ? n / len : out->geometricNormal;
    out->shadingNormal = dot(n, out->geometricNormal) < 0 ? -n : n;
}

void TriangleMesh::sampleArea(Vec2 u, Vec3* position, Vec3* normal) const {
    float uRemapped;
    const int tri = triangleByArea_.sample(u.x, nullptr, &uRemapped);
    const Vec2 b = squareToUniformTriangle(Vec2(uRemapped, u.y));
    const Vec3& p0 = data_.positions[data_.indices[3 * tri]];
    const Vec3& p1 = data_.positions[data_.indices[3 * tri + 1]];
    const Vec3& p2 = data_.positions[data_.indices[3 * tri + 2]];
    *position = p0 * b.x + p1 * b.y + p2 * (1 - b.x - b.y);
    *normal = faceNormal(static_cast<uint32_t>(tri));
}

}  // namespace rr
