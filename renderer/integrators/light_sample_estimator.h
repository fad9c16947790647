// Next-event estimation by light sampling (`light`), alone or combined with the integrator's
// scattering samples by the power heuristic (`mis`, Veach 1997 §9.2, with sample counts):
// (1/n) Σ f·Le·V·w / p over n light samples, each a light chosen by the scene's selector (or a
// technique's guide) and a point on it.
#pragma once

#include <algorithm>
#include <array>
#include <span>

#include "integrators/direct_lighting_estimator.h"

namespace rr {

class LightSampleEstimator final : public DirectLightingEstimator {
  public:
    LightSampleEstimator(uint32_t lightSamples, bool multipleImportance)
        : DirectLightingEstimator(this), lightSamples_(lightSamples), mis_(multipleImportance) {}

    std::string name() const override { return mis_ ? "mis" : "light"; }
    nlohmann::json parameters() const override;
    uint32_t lightSamples() const override { return lightSamples_; }
    FoundEmission foundEmission() const override {
        return mis_ ? FoundEmission::Weighted : FoundEmission::Excluded;
    }
    void estimate(ShadingPoint& point) const override { estimateAt(point); }
    // The estimate at a shading point of the integrator's own (final) type, whose calls are then
    // direct: the hot loop of `direct` and of path vertices.
    template <class Point>
    void estimateAt(Point& point) const;

  private:
    uint32_t lightSamples_;
    bool mis_;
};

template <class Point>
void LightSampleEstimator::estimateAt(Point& point) const {
    const float n = static_cast<float>(lightSamples_);
    // Points whose guide draws light samples in batches get them 16 at a time, so that the
    // lights overlap their table reads (ShadingPoint::sampleLights); the draws are the same.
    constexpr uint32_t kBatch = 16;
    std::array<LightDraw, kBatch> batch;
    for (uint32_t r = 0; r < lightSamples_; ++r) {
        if constexpr (Point::kDrawsLightBatches) {
            if (r % kBatch == 0) {
                std::array<uint32_t, kBatch> repeats;
                const uint32_t count = std::min(kBatch, lightSamples_ - r);
                for (uint32_t k = 0; k < count; ++k)
                    repeats[k] = r + k;
                point.sampleLights(std::span(repeats.data(), count), lightSamples_,
                                   /*standIns=*/nullptr, batch.data());
            }
        }
        LightSample ls;
        float pdf;
        const Light* light;
        if constexpr (Point::kDrawsLightBatches) {
            const LightDraw& draw = batch[r % kBatch];
            if (!draw.drawn) continue;
            ls = draw.sample;
            pdf = draw.pdf;
            light = draw.light;
        } else if (!point.sampleLight(r, lightSamples_, /*standIns=*/nullptr, &ls, &pdf, &light)) {
            continue;
        }
        const Rgb f = point.scattering(ls.direction);
        if (f.isBlack()) continue;
        float survival;
        const Rgb tr = point.visibility(ls, light->isInfinite(), &survival);
        if (tr.isBlack()) continue;
        // A delta light cannot be found by scattering: its samples count in full.
        const float weight = mis_ && !ls.isDelta
                                 ? powerHeuristic(n, pdf, point.scatteringSamples(),
                                                  point.scatteringPdf(ls.direction) * survival)
                                 : 1.0f;
        point.add(point.contribution(f, ls.radiance, tr, weight, pdf * n));
    }
}

// Runs `estimator` at `point`, light sampling without the interface's indirection.
template <class Point>
void runEstimator(const DirectLightingEstimator& estimator, Point& point) {
    if (const LightSampleEstimator* light = estimator.lightSampling())
        light->estimateAt(point);
    else
        estimator.estimate(point);
}

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
