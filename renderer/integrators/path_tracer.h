// Unidirectional path tracing (Kajiya 1986) with two strategies for finding light:
//  - `path`: BSDF (and phase-function) sampling only; emission counts when a path hits an
//    emitter.
//  - `path_mis`: next-event estimation at every non-specular vertex, on surfaces and in media,
//    plus BSDF or phase sampling, combined with Veach's power heuristic (Veach & Guibas 1995).
// Path length: `maxDepth` scattering events, on surfaces or in media (−1: unlimited up to a
// safety cap), Russian roulette from `rrDepth` on with survival probability
// min(1, max throughput · Πη²).
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

#include "integrators/integrator.h"

namespace rr {

struct PathSettings {
    int maxDepth = 16;
    int rrDepth = 4;
};

class PathTracer final : public SampleIntegrator {
  public:
    // Hard cap on "unlimited" paths (max_depth −1): only pathological scenes (a closed glass
    // shell with total internal reflection) ever reach it.
    static constexpr int kDepthCap = 1000;

    PathTracer(const PathSettings& settings, bool nextEventEstimation)
        : settings_(settings), nee_(nextEventEstimation) {}

    std::string name() const override { return nee_ ? "path_mis" : "path"; }
    nlohmann::json parameters() const override;
    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                 RayCounters& rays) const override;
    bool supportsMedia() const override { return true; }

  private:
    PathSettings settings_;
    bool nee_;
};

}  // namespace rr
