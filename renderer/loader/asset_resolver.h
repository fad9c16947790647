// Finds asset files (meshes, environment maps) referenced by relative path in scene files.
// Search order: the scene file's directory, $RENDERER_ASSETS (':'-separated), the
// repository's git-ignored `assets/`, then `../shared/assets` beside the repository.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rr {

// A file found on the search path, as it was when found. A scene built from it and kept by a
// long-lived process (`renderer serve`) is stale once the name resolves elsewhere or the file
// changes.
struct AssetStamp {
    std::string name;
    std::filesystem::path path;
    std::uintmax_t size = 0;
    std::filesystem::file_time_type modified;
    bool operator==(const AssetStamp&) const = default;
};

class AssetResolver {
  public:
    explicit AssetResolver(std::vector<std::filesystem::path> searchPath)
        : searchPath_(std::move(searchPath)) {}

    // The standard search path for a scene file in `sceneDirectory`.
    static AssetResolver standard(const std::filesystem::path& sceneDirectory);

    std::optional<std::filesystem::path> resolve(const std::string& relativePath) const;
    // `name` resolved now, with its size and modification time.
    std::optional<AssetStamp> stamp(const std::string& name) const;
    // A resolver searching the same path that also appends the stamp of every file it finds
    // to `log`, which must outlive it.
    AssetResolver recordingInto(std::vector<AssetStamp>* log) const;

    const std::vector<std::filesystem::path>& searchPath() const { return searchPath_; }
    // Human-readable list of the directories searched, for error messages.
    std::string describe() const;

  private:
    std::optional<std::filesystem::path> find(const std::string& relativePath) const;

    std::vector<std::filesystem::path> searchPath_;
    std::vector<AssetStamp>* log_ = nullptr;
};

}  // namespace rr
