// The scenes a long-lived process (`renderer serve`) has built, so that a run of renders of
// one scene with different seeds, sample counts or integrators loads its assets and builds its
// acceleration structure once. A scene is immutable once built, so sharing one between renders
// cannot change their pixels (tests/test_serve.py checks them against separate processes).
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <string>
#include <vector>

#include "loader/asset_resolver.h"
#include "scene/scene.h"

namespace rr {

class SceneCache {
  public:
    explicit SceneCache(size_t capacity) : capacity_(capacity) {}

    // The scene built for `key` (scene_loader.cpp makes it from everything the scene is built
    // from), or null; also null, and the entry dropped, when one of the scene's files now
    // resolves elsewhere through `assets` or has changed. A hit becomes the most recently
    // used entry.
    std::shared_ptr<const Scene> find(const std::string& key, const AssetResolver& assets);
    // Adds a scene built from the files `assets` names, dropping the least recently used
    // entry beyond the capacity.
    void insert(const std::string& key, std::shared_ptr<const Scene> scene,
                std::vector<AssetStamp> assets);

  private:
    struct Entry {
        std::string key;
        std::shared_ptr<const Scene> scene;
        std::vector<AssetStamp> assets;
    };

    size_t capacity_;
    std::list<Entry> entries_;  // most recent first
};

}  // namespace rr
