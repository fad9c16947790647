// Triangle meshes from PLY and OBJ files, through Assimp.
#pragma once

#include <filesystem>
#include <string>

#include "io/mesh_data.h"

namespace rr {

// Throws std::runtime_error with Assimp's message when the file cannot be read.
MeshData loadMesh(const std::filesystem::path& file);

}  // namespace rr
