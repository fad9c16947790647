// Unidirectional path tracing (Kajiya 1986) with two strategies for finding light:
//  - `path`: BSDF (and phase-function) sampling only; emission counts when a path hits an
//    emitter.
//  - `path_mis`: next-event estimation at every non-specular vertex, on surfaces and in media,
//    by a direct-lighting estimator (direct_lighting_estimator.h; by default `mis`: light
//    sampling and the path's BSDF or phase sampling combined with Veach's power heuristic,
//    Veach & Guibas 1995).
// Path length: `maxDepth` scattering events, on surfaces or in media (−1: unlimited up to a
// safety cap), Russian roulette from `rrDepth` on with survival probability
// q = min(1, max throughput · Πη²) wherever q < `rrThreshold` (a path whose throughput is
// still large runs on untouched), or a fixed `rrSurvival` (pbrt-v1's 0.5) when one is set.
// Every rule is unbiased: a surviving path is weighted by 1/q.
//
// Participating media (the volume rendering equation; Pharr, Jakob & Humphreys, PBR 3rd ed.,
// ch. 15): every segment inside a medium samples a free-flight distance (the MediumDistance
// decision of the vertex it leads to). A collision makes a medium vertex: next-event estimation
// with the phase function (path_mis), then the phase function samples the direction (the
// BsdfDirection decision of that vertex). Passing the segment multiplies the throughput by Tr/S
// (medium.h), which also attenuates emission found and radiance escaping to infinite lights; S
// joins the BSDF or phase density in the MIS weights (it is the probability of reaching the light).
// Shadow rays carry the transmittance of the media they cross. Shapes with an interior medium but
// no material are index-matched boundaries: the path passes through them without a scattering
// event. Scenes without media run a separately compiled walk that contains none of this.
#pragma once

#include <algorithm>
#include <memory>

#include "integrators/direct_lighting_estimator.h"
#include "integrators/integrator.h"
#include "integrators/pixel_records.h"

namespace rr {

struct PathSettings {
    int maxDepth = 16;
    // Russian roulette from the first vertex, played only where the throughput-driven survival
    // probability is below 0.25: the rule of best geometric-mean efficiency over the paper
    // scenes (results/tables/rr_efficiency.md).
    int rrDepth = 1;
    // Russian roulette's survival probability: 0 for min(1, max throughput component × η²),
    // else this fixed value (pbrt-v1's path integrator: 0.5).
    float rrSurvival = 0;
    // The throughput-driven survival probability is played only where it is below this (1:
    // wherever it is below 1). A fixed rrSurvival is played always and ignores it.
    float rrThreshold = 0.25f;

    // Adds max_depth, rr_depth and the survival rule (rr_survival when fixed, else
    // rr_threshold) to an integrator's parameters.
    void addTo(nlohmann::json* parameters) const;
};

class PathTracer final : public SampleIntegrator {
  public:
    // Hard cap on "unlimited" paths (max_depth −1): only pathological scenes (a closed glass
    // shell with total internal reflection) ever reach it.
    static constexpr int kDepthCap = 1000;

    // `path`: next-event estimation by the `bsdf` estimator, which samples no light.
    static std::unique_ptr<PathTracer> withoutNextEventEstimation(const PathSettings& settings);
    // `path_mis`.
    PathTracer(const PathSettings& settings, std::unique_ptr<DirectLightingEstimator> nee)
        : PathTracer("path_mis", settings, std::move(nee)) {}

    std::string name() const override { return name_; }
    nlohmann::json parameters() const override;
    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                 RayCounters& rays) const override;

    uint32_t decisionRepeats() const override { return std::max(1u, nee_->decisionRepeats()); }
    // Refuses an estimator that cannot work in the scene's media.
    void prepare(const Scene& scene) override;
    // The estimator's records at each pixel sample's first hit (pixel_records.h).
    void beginImage(int width, int height, bool iterated) override {
        records_.begin(width, height, iterated, nee_->pixelRecords(), "/integrator/estimator");
    }
    void commitPixelRecords() override { records_.commit(); }
    std::vector<AuxiliaryChannel> auxiliaryChannels() const override { return records_.channels(); }

  private:
    PathTracer(std::string name, const PathSettings& settings,
               std::unique_ptr<DirectLightingEstimator> nee)
        : name_(std::move(name)), settings_(settings), nee_(std::move(nee)) {}

    std::string name_;
    PathSettings settings_;
    std::unique_ptr<DirectLightingEstimator> nee_;
    // Written by estimate() at pixels its caller renders alone (render_schedule.h).
    mutable PixelRecords records_;
};

}  // namespace rr
