// Triangle meshes from PLY files (our own reader, io/ply_reader) and OBJ files (Assimp).
#pragma once

#include <filesystem>
#include <string>

#include "io/mesh_data.h"

namespace rr {

// Throws std::runtime_error naming the file and what is wrong when it cannot be read, has no
// triangles or a vertex that is not finite.
MeshData loadMesh(const std::filesystem::path& file);

}  // namespace rr
