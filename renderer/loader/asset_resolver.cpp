#include "loader/asset_resolver.h"

#include <cstdlib>
#include <sstream>

namespace rr {

namespace fs = std::filesystem;

AssetResolver AssetResolver::standard(const fs::path& sceneDirectory) {
    std::vector<fs::path> path{sceneDirectory};
    if (const char* env = std::getenv("RENDERER_ASSETS")) {
        std::stringstream list(env);
        std::string entry;
        while (std::getline(list, entry, ':'))
            if (!entry.empty()) path.emplace_back(entry);
    }
    const fs::path repository = RENDERER_SOURCE_DIR;  // set by CMake
    path.push_back(repository / "assets");
    path.push_back(repository.parent_path() / "shared" / "assets");
    return AssetResolver(std::move(path));
}

std::optional<fs::path> AssetResolver::resolve(const std::string& relativePath) const {
    if (!log_) return find(relativePath);
    std::optional<AssetStamp> found = stamp(relativePath);
    if (!found) return std::nullopt;
    log_->push_back(*found);
    return found->path;
}

std::optional<AssetStamp> AssetResolver::stamp(const std::string& name) const {
    const std::optional<fs::path> path = find(name);
    if (!path) return std::nullopt;
    std::error_code size, time;
    AssetStamp s{name, *path, fs::file_size(*path, size), fs::last_write_time(*path, time)};
    if (size || time) return std::nullopt;  // vanished between the two looks
    return s;
}

AssetResolver AssetResolver::recordingInto(std::vector<AssetStamp>* log) const {
    AssetResolver recording(searchPath_);
    recording.log_ = log;
    return recording;
}

std::optional<fs::path> AssetResolver::find(const std::string& relativePath) const {
    const fs::path p(relativePath);
    if (p.is_absolute()) return fs::is_regular_file(p) ? std::optional(p) : std::nullopt;
    for (const fs::path& dir : searchPath_) {
        std::error_code ec;
        const fs::path candidate = dir / p;
        if (fs::is_regular_file(candidate, ec)) return candidate.lexically_normal();
    }
    return std::nullopt;
}

std::string AssetResolver::describe() const {
    std::string s;
    for (const fs::path& dir : searchPath_)
        s += (s.empty() ? "" : ", ") + dir.string();
    return s;
}

}  // namespace rr
