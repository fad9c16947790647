// Indexed triangle mesh (Embree triangle geometry). Geometric normals follow the right-hand
// rule on (v0, v1, v2); optional smooth shading normals are vertex-averaged at load time.
#pragma once

#include <cstdint>
#include <vector>

#include "sampling/distribution1d.h"
#include "scene/shape.h"

namespace rr {

struct MeshData {
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;  // 3 per triangle
    std::vector<Vec3> normals;      // empty, or one per position
};

class TriangleMesh final : public Shape {
  public:
    explicit TriangleMesh(MeshData data);

    RTCGeometry createGeometry(RTCDevice device) const override;
    void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const override;
    float area() const override { return area_; }
    void sampleArea(Vec2 u, Vec3* position, Vec3* normal) const override;

    size_t triangleCount() const { return data_.indices.size() / 3; }
    // Averages face normals (area-weighted) into per-vertex shading normals.
    static std::vector<Vec3> smoothNormals(const MeshData& data);

  private:
    Vec3 faceNormal(uint32_t triangle) const;

    MeshData data_;
    float area_ = 0;
    Distribution1D triangleByArea_;
};

}  // namespace rr
