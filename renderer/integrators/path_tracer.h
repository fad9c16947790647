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
//
// Both are PathTracer<StandardSampling>. A technique assembles its own path tracer from the same
// walk with its own guide (how the path's decisions are made, standard_sampling.h), its own
// light-selection policy (StandardSamplingWith<Policy>), or both, as PathTracer<Guide>; the
// walk is a template on the guide, so each instance is compiled on its own and the standard one
// pays nothing for the others (renderer/README.md, "Building on path_mis").
#pragma once

#include <algorithm>
#include <memory>
#include <string>

#include "integrators/direct_lighting_estimator.h"
#include "integrators/integrator.h"
#include "integrators/path_settings.h"
#include "integrators/path_walk.h"
#include "integrators/pixel_records.h"
#include "integrators/standard_sampling.h"

namespace rr {

// Everything of a path tracer but the guide: its name, settings and next-event estimator, the
// estimator's preparation and pixel records.
class PathTracerBase : public SampleIntegrator {
  public:
    std::string name() const override { return name_; }
    LightTransport transport() const override { return LightTransport::Paths; }
    bool samplesLights() const override { return nee_->samplesLights(); }
    nlohmann::json parameters() const override;

    uint32_t decisionRepeats() const override { return std::max(1u, nee_->decisionRepeats()); }
    // Refuses an estimator that cannot work in the scene's media.
    void prepare(const Scene& scene) override;
    // The estimator's records at each pixel sample's first hit (pixel_records.h).
    void beginImage(int width, int height, bool iterated) override {
        records_.begin(width, height, iterated, nee_->pixelRecords(), "/integrator/estimator");
    }
    void commitPixelRecords() override { records_.commit(); }
    std::vector<AuxiliaryChannel> auxiliaryChannels() const override { return records_.channels(); }

  protected:
    // `name`: the integrator's type as scenes name it; `nee`: next-event estimation at every
    // non-specular vertex (ScatteringOnlyEstimator: none, as in `path`).
    PathTracerBase(std::string name, const PathSettings& settings,
                   std::unique_ptr<DirectLightingEstimator> nee)
        : name_(std::move(name)), settings_(settings), nee_(std::move(nee)) {}

    // One path of pixel (x, y) with `guide`.
    template <PathGuide Guide>
    Rgb trace(const Scene& scene, Guide& guide, int x, int y, RayCounters& rays) const {
        return tracePath(scene, guide, x, y, settings_, *nee_, rays, records_.slot(x, y));
    }

  private:
    std::string name_;
    PathSettings settings_;
    std::unique_ptr<DirectLightingEstimator> nee_;
    // Written by estimate() at pixels its caller renders alone (render_schedule.h).
    mutable PixelRecords records_;
};

// Makes each pixel sample's guide as Guide(scene, sample): for guides that need nothing else,
// StandardSamplingWith<Policy> among them when the policy is made from the scene alone.
template <class Guide>
struct ConstructGuide {
    Guide operator()(const Scene& scene, const PixelSample& sample) const {
        return Guide(scene, sample);
    }
};

// A path tracer whose decisions each pixel sample's guide makes, the guide made by
// `makeGuide(scene, sample)`: a guide or policy that needs state of the integrator's gets it
// from a MakeGuide object that holds it.
template <PathGuide Guide = StandardSampling, class MakeGuide = ConstructGuide<Guide>>
class PathTracer : public PathTracerBase {
  public:
    PathTracer(std::string name, const PathSettings& settings,
               std::unique_ptr<DirectLightingEstimator> nee, MakeGuide makeGuide = {})
        : PathTracerBase(std::move(name), settings, std::move(nee)),
          makeGuide_(std::move(makeGuide)) {}

    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                 RayCounters& rays) const override {
        Guide guide = makeGuide_(scene, sample);
        return trace(scene, guide, x, y, rays);
    }

  private:
    MakeGuide makeGuide_;
};

// `path` and `path_mis`, compiled once (path_tracer.cpp).
extern template class PathTracer<StandardSampling>;

}  // namespace rr
