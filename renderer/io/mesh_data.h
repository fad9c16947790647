// An indexed triangle mesh as read from a file: what io/mesh_io produces and the scene's
// TriangleMesh shape is built from.
#pragma once

#include <cstdint>
#include <vector>

#include "math/vector.h"

namespace rr {

struct MeshData {
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;  // 3 per triangle
    std::vector<Vec3> normals;      // empty, or one per position
};

}  // namespace rr
