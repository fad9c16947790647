// The scenes a long-lived process (`renderer serve`) has built, so that a run of renders of
// one scene with different seeds, sample counts or integrators loads its assets and builds its
// acceleration structure once. A scene is immutable once built, so sharing one between renders
// cannot change their pixels (tests/test_serve.py checks them against separate processes).
#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <string>
#include <utility>

#include "config/json_reader.h"
#include "loader/asset_resolver.h"
#include "scene/scene.h"

namespace rr {

class SceneCache {
  public:
    explicit SceneCache(size_t capacity) : capacity_(capacity) {}

    // What identifies the built scene: the document without what only the integrator and the
    // render schedule read (/integrator, /render/seed, /render/spp; /description, which
    // nothing reads), and where its assets are found.
    static std::string key(const Json& document, const AssetResolver& assets);

    // The scene built for `key`, or null; a hit becomes the most recently used entry.
    std::shared_ptr<const Scene> find(const std::string& key);
    // Adds a scene, dropping the least recently used one beyond the capacity.
    void insert(const std::string& key, std::shared_ptr<const Scene> scene);

  private:
    size_t capacity_;
    std::list<std::pair<std::string, std::shared_ptr<const Scene>>> entries_;  // most recent first
};

}  // namespace rr
