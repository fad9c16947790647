// Chooses which light next-event estimation samples. One interface for uniform and
// power-proportional selection; adaptive techniques (TAIS's light-selection map, PMC-HI
// mixtures) supply their own implementation.
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "sampling/distribution1d.h"
#include "scene/light.h"

namespace rr {

class LightSelector {
  public:
    virtual ~LightSelector() = default;
    // Picks a light for `reference` with probability *pmf; nullptr when there are none.
    virtual const Light* select(float u, const Vec3& reference, float* pmf) const = 0;
    // Probability that select() picks `light` for `reference`.
    virtual float pmf(const Light& light, const Vec3& reference) const = 0;
};

enum class LightSelection : uint8_t { Uniform, Power };

std::unique_ptr<LightSelector> makeLightSelector(LightSelection kind,
                                                 std::span<const Light* const> lights);

}  // namespace rr
