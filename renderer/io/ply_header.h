// A strict check of a PLY file's header, before Assimp reads it: Debian's Assimp 5.2 crashes
// (a SEGV in its PLY importer) on some malformed headers that `make fuzz` found
// (tests/fuzz/regressions/ply/). The check reads the header only: printable lines, known
// keywords and types, element counts below 2^31, a vertex element with x, y and z, and for a
// binary body at least the bytes its elements' fixed parts need.
#pragma once

#include <filesystem>

namespace rr {

// Throws std::runtime_error naming the file and what is wrong.
void checkPlyHeader(const std::filesystem::path& file);

}  // namespace rr
