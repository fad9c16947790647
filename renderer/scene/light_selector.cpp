#include "scene/light_selector.h"

#include <vector>

namespace rr {

namespace {

// Selection from a fixed discrete distribution (uniform or by power).
class TableLightSelector final : public LightSelector {
  public:
    TableLightSelector(std::span<const Light* const> lights, std::span<const float> weights)
        : lights_(lights.begin(), lights.end()), table_(weights) {}

    const Light* select(float u, const Vec3&, float* pmf) const override {
        if (lights_.empty()) return nullptr;
        return lights_[table_.sample(u, pmf)];
    }
    float pmf(const Light& light, const Vec3&) const override { return table_.pmf(light.index()); }

  private:
    std::vector<const Light*> lights_;
    Distribution1D table_;
};

}  // namespace

std::unique_ptr<LightSelector> makeLightSelector(LightSelection kind,
                                                 std::span<const Light* const> lights) {
    std::vector<float> weights(lights.size(), 1.0f);
    if (kind == LightSelection::Power)
        for (size_t i = 0; i < lights.size(); ++i)
            weights[i] = lights[i]->power().luminance();
    return std::make_unique<TableLightSelector>(lights, weights);
}

}  // namespace rr
