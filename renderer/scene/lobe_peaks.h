// A material capability: the directions where its lobes peak (mirror, retro-reflection, lobe
// axes, an anisotropic lobe's cone), for estimators that split the sphere of directions there
// (two-stage sampling's initial splits, Cline et al. 2006 §2.2). A material that knows its
// peaks also implements LobePeakSource; an estimator that needs them finds it once per material
// when it is prepared (lobePeakSource) and refuses a scene whose materials lack it, so a new
// material need not know them.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <vector>

#include "math/vector.h"
#include "scene/material.h"

namespace rr {

// Up to 16 peak directions (local frame): mirror, retro-reflection, anisotropic cone peaks.
struct LobePeaks {
    std::array<Vec3, 16> directions;
    int count = 0;
    void add(const Vec3& w) {
        if (count < static_cast<int>(directions.size())) directions[count++] = w;
    }
};

class LobePeakSource {
  public:
    virtual ~LobePeakSource() = default;
    // Adds to *out the directions (local frame) where the lobes seen from `wo` peak. Asked only
    // of sources that find them (lobePeakSource).
    virtual void peaks(const ShadingContext& ctx, const Vec3& wo, LobePeaks* out) const = 0;
    // Whether peaks() knows them all: false for a material made of others (mix, checker) when a
    // part does not.
    virtual bool findsPeaks() const { return true; }
};

// The lobe peaks of `material`, or nullptr when it does not know them.
inline const LobePeakSource* lobePeakSource(const Material& material) {
    const auto* source = dynamic_cast<const LobePeakSource*>(&material);
    return source && source->findsPeaks() ? source : nullptr;
}

// The lobe peaks of a scene's materials, found once (when an estimator is prepared), by material
// index (Material::index).
class LobePeakSources {
  public:
    explicit LobePeakSources(std::span<const std::unique_ptr<Material>> materials) {
        for (const auto& material : materials)
            byIndex_.push_back(lobePeakSource(*material));
    }
    LobePeakSources() = default;

    // `material`'s peaks, or nullptr when it does not know them.
    const LobePeakSource* of(const Material& material) const {
        return byIndex_[static_cast<size_t>(material.index())];
    }

  private:
    std::vector<const LobePeakSource*> byIndex_;
};

}  // namespace rr
