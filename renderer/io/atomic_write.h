// Writes a file through a temporary sibling renamed into place, so readers never see a
// half-written result (an interrupted run leaves the old file, or none).
#pragma once

#include <filesystem>
#include <functional>

namespace rr {

// Calls write(temporaryPath), then renames it to `destination`. The temporary keeps the
// destination's extension (image libraries choose the format by it). Removes the temporary
// and rethrows if write throws.
void writeAtomically(const std::filesystem::path& destination,
                     const std::function<void(const std::filesystem::path&)>& write);

}  // namespace rr
