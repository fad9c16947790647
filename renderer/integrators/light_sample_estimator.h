// Next-event estimation by light sampling (`light`), alone or combined with the integrator's
// scattering samples by the power heuristic (`mis`, Veach 1997 §9.2, with sample counts):
// (1/n) Σ f·Le·V·w / p over n light samples, each a light chosen by the scene's selector (or a
// technique's guide) and a point on it.
#pragma once

#include "integrators/direct_lighting_estimator.h"

namespace rr {

class LightSampleEstimator final : public DirectLightingEstimator {
  public:
    LightSampleEstimator(uint32_t lightSamples, bool multipleImportance)
        : lightSamples_(lightSamples), mis_(multipleImportance) {}

    std::string name() const override { return mis_ ? "mis" : "light"; }
    nlohmann::json parameters() const override;
    uint32_t lightSamples() const override { return lightSamples_; }
    FoundEmission foundEmission() const override {
        return mis_ ? FoundEmission::Weighted : FoundEmission::Excluded;
    }
    void estimate(ShadingPoint& point) const override;

  private:
    uint32_t lightSamples_;
    bool mis_;
};

// No light samples: emission is found by the integrator's scattering samples alone (`bsdf`).
class ScatteringOnlyEstimator final : public DirectLightingEstimator {
  public:
    std::string name() const override { return "bsdf"; }
    nlohmann::json parameters() const override { return {{"type", name()}}; }
    uint32_t lightSamples() const override { return 0; }
    FoundEmission foundEmission() const override { return FoundEmission::Full; }
    void estimate(ShadingPoint&) const override {}
};

}  // namespace rr
