// Unidirectional path tracing (Kajiya 1986) with two strategies for finding light:
//  - `path`: BSDF sampling only; emission counts when a path hits an emitter.
//  - `path_mis`: next-event estimation at every non-specular vertex plus BSDF sampling,
//    combined with Veach's power heuristic (Veach & Guibas 1995).
// Path length: `maxDepth` scattering events (−1: unlimited up to a safety cap), Russian
// roulette from `rrDepth` on with survival probability min(1, max throughput · Πη²).
#pragma once

#include "integrators/integrator.h"

namespace rr {

struct PathSettings {
    int maxDepth = 16;
    int rrDepth = 4;
};

class PathTracer final : public Integrator {
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

  private:
    // Next-event estimate at a vertex, MIS-weighted against BSDF sampling.
    Rgb sampleLight(const Scene& scene, const SurfaceHit& hit, const Material& material,
                    const ShadingContext& ctx, const Frame& frame, const Vec3& wo,
                    const PixelSample& sample, uint32_t vertex, RayCounters& rays) const;

    PathSettings settings_;
    bool nee_;
};

}  // namespace rr
