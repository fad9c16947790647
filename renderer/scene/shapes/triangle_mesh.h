// Indexed triangle mesh (Embree triangle geometry). Geometric normals follow the right-hand
// rule on (v0, v1, v2); optional smooth shading normals are vertex-averaged at load time.
#pragma once

#include <cstdint>
#include <vector>

#include "io/mesh_data.h"
#include "sampling/distribution1d.h"
#include "scene/shape.h"

namespace rr {

class TriangleMesh final : public Shape {
  public:
    explicit TriangleMesh(MeshData data);

    RTCGeometry createGeometry(RTCDevice device) const override;
    void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const override;
    float area() const override { return area_; }
    ShapeSample sampleArea(Vec2 u) const override;

    size_t triangleCount() const { return data_.indices.size() / 3; }
    // Averages face normals (area-weighted) into per-vertex shading normals.
    static std::vector<Vec3> smoothNormals(const MeshData& data);

  private:
    struct Triangle {
        Vec3 p0, p1, p2;
        Vec3 normal() const { return normalize(cross(p1 - p0, p2 - p0)); }  // right-hand rule
        float errorScale() const;
    };
    Triangle triangle(uint32_t index) const;

    MeshData data_;
    float area_ = 0;
    Distribution1D triangleByArea_;
};

}  // namespace rr
