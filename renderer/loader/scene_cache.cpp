#include "loader/scene_cache.h"

namespace rr {

std::string SceneCache::key(const Json& document, const AssetResolver& assets) {
    Json scene = document;
    if (scene.is_object()) {
        scene.erase("integrator");
        scene.erase("description");
        const auto render = scene.find("render");
        if (render != scene.end() && render->is_object()) {
            render->erase("seed");
            render->erase("spp");
        }
    }
    return assets.describe() + '\n' + scene.dump();
}

std::shared_ptr<const Scene> SceneCache::find(const std::string& key) {
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
        if (it->first != key) continue;
        entries_.splice(entries_.begin(), entries_, it);
        return entries_.front().second;
    }
    return nullptr;
}

void SceneCache::insert(const std::string& key, std::shared_ptr<const Scene> scene) {
    if (capacity_ == 0) return;
    entries_.emplace_front(key, std::move(scene));
    while (entries_.size() > capacity_)
        entries_.pop_back();
}

}  // namespace rr
