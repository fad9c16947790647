// Finds asset files (meshes, environment maps) referenced by relative path in scene files.
// Search order: the scene file's directory, $RENDERER_ASSETS (':'-separated), the
// repository's git-ignored `assets/`, then `../shared/assets` beside the repository.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rr {

class AssetResolver {
  public:
    explicit AssetResolver(std::vector<std::filesystem::path> searchPath)
        : searchPath_(std::move(searchPath)) {}

    // The standard search path for a scene file in `sceneDirectory`.
    static AssetResolver standard(const std::filesystem::path& sceneDirectory);

    std::optional<std::filesystem::path> resolve(const std::string& relativePath) const;
    // Human-readable list of the directories searched, for error messages.
    std::string describe() const;

  private:
    std::vector<std::filesystem::path> searchPath_;
};

}  // namespace rr
