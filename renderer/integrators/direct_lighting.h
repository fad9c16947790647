// Direct illumination only (emission seen by the camera plus one bounce to a light), with a
// choice of strategy: `light` (next-event estimation), `bsdf` (BSDF sampling) or `mis` (both,
// power heuristic with sample counts, Veach 1997 §9.2). `lightSamples` and `bsdfSamples`
// draws per pixel sample are stratified together by structured samplers.
#pragma once

#include <algorithm>

#include "integrators/integrator.h"

namespace rr {

enum class DirectStrategy : uint8_t { Light, Bsdf, Mis };

struct DirectSettings {
    DirectStrategy strategy = DirectStrategy::Mis;
    int lightSamples = 1;
    int bsdfSamples = 1;
};

class DirectLighting final : public SampleIntegrator {
  public:
    explicit DirectLighting(const DirectSettings& settings) : settings_(settings) {}

    std::string name() const override { return "direct"; }
    nlohmann::json parameters() const override;
    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                 RayCounters& rays) const override;
    uint32_t decisionRepeats() const override {
        return static_cast<uint32_t>(std::max(settings_.lightSamples, settings_.bsdfSamples));
    }

  private:
    bool usesLights() const { return settings_.strategy != DirectStrategy::Bsdf; }
    bool usesBsdf() const { return settings_.strategy != DirectStrategy::Light; }
    // MIS weight of one strategy's sample given both densities (1 when not combining).
    float weight(float nSelf, float pdfSelf, float nOther, float pdfOther) const;
    // The infinite lights seen by a BSDF sample that escaped in direction `w`, weighted and
    // divided by the number of BSDF samples like emission found on a surface.
    Rgb escapedToInfiniteLights(const Scene& scene, const Vec3& w, const Vec3& reference,
                                const BsdfSample& bs, float nBsdf, float nLight) const;

    DirectSettings settings_;
};

const char* directStrategyName(DirectStrategy s);

}  // namespace rr
