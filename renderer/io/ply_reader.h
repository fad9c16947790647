// Triangle meshes from PLY files (ASCII, or binary in either byte order), read by our own strict
// reader rather than Assimp: `make fuzz` found malformed files on which Debian's Assimp 5.2
// crashes (a SEGV on a header) or calls abort() (in its ASCII body parser); the inputs are kept
// in tests/fuzz/regressions/ply/. Debian packages no other PLY library.
//
// Read: the vertex element's x, y, z and the face element's `vertex_indices` (or `vertex_index`)
// list, fanned into triangles; other elements and properties (file normals too: a mesh's
// normals are geometric or smooth, computed by the scene) are parsed and skipped. Vertices with
// identical position bits are joined, so smooth normals see the sharing, and triangles with two
// equal corners are dropped.
#pragma once

#include <filesystem>

#include "io/mesh_data.h"

namespace rr {

// Throws std::runtime_error naming the file and what is wrong: an unknown keyword or type, a
// count that the body does not hold, a number that does not parse or does not fit its type, an
// index past the vertices, bytes left after the last element.
MeshData readPly(const std::filesystem::path& file);

}  // namespace rr
