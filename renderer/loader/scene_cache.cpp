#include "loader/scene_cache.h"

#include <algorithm>

namespace rr {

std::shared_ptr<const Scene> SceneCache::find(const std::string& key, const AssetResolver& assets) {
    const auto it = std::find_if(entries_.begin(), entries_.end(),
                                 [&](const Entry& e) { return e.key == key; });
    if (it == entries_.end()) return nullptr;
    const bool current =
        std::all_of(it->assets.begin(), it->assets.end(),
                    [&](const AssetStamp& s) { return assets.stamp(s.name) == s; });
    if (!current) {
        entries_.erase(it);
        return nullptr;
    }
    entries_.splice(entries_.begin(), entries_, it);
    return entries_.front().scene;
}

void SceneCache::insert(const std::string& key, std::shared_ptr<const Scene> scene,
                        std::vector<AssetStamp> assets) {
    if (capacity_ == 0) return;
    entries_.push_front({key, std::move(scene), std::move(assets)});
    while (entries_.size() > capacity_)
        entries_.pop_back();
}

}  // namespace rr
