// Unidirectional path tracing (Kajiya 1986) with two strategies for finding light:
//  - `path`: BSDF (and phase-function) sampling only; emission counts when a path hits an
//    emitter.
//  - `path_mis`: next-event estimation at every non-specular vertex, on surfaces and in media,
//    plus BSDF or phase sampling, combined with Veach's power heuristic (Veach & Guibas 1995).
// Path length: `maxDepth` scattering events, on surfaces or in media (−1: unlimited up to a
// safety cap), Russian roulette from `rrDepth` on with survival probability
// min(1, max throughput · Πη²).
//
// Participating media (the volume rendering equation, e.g. Pharr et al., pbrt 3rd ed. §15.2):
// every segment inside a medium samples a free-flight distance (the MediumDistance decision of
// the vertex it leads to). A collision makes a medium vertex: next-event estimation with the
// phase function (path_mis), then the phase function samples the direction (the BsdfDirection
// decision of that vertex). Passing the segment multiplies the throughput by Tr/S, which also
// attenuates emission found and radiance escaping to infinite lights. Shadow rays carry the
// transmittance of the media they cross. Shapes with an interior medium but no material are
// index-matched boundaries: the path passes through them without a scattering event. Scenes
// without media take none of these branches.
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
    bool supportsMedia() const override { return true; }

  private:
    struct PathState;

    int maxDepth() const { return settings_.maxDepth < 0 ? kDepthCap : settings_.maxDepth; }

    // Free flight along the current ray up to `tMax` inside the current medium: true with the
    // collision distance in `*t`, false when the flight passes (throughput updated either way).
    bool flyThroughMedium(PathState& s, float tMax, const PixelSample& sample, float* t) const;
    // Emission of the shape at `hit` times the throughput, MIS-weighted against next-event
    // estimation.
    Rgb emission(const Scene& scene, const PathState& s, const SurfaceHit& hit) const;
    // Continues the ray through an index-matched boundary into the medium beyond.
    bool passThroughBoundary(const Scene& scene, PathState& s, const SurfaceHit& hit,
                             RayCounters& rays) const;
    // A surface vertex: next-event estimation and BSDF sampling. False when the path ends.
    bool scatterAtSurface(const Scene& scene, PathState& s, const SurfaceHit& hit,
                          const PixelSample& sample, Rgb* radiance, RayCounters& rays) const;
    // A medium vertex at distance `t` along the ray: next-event estimation and phase sampling.
    bool scatterInMedium(const Scene& scene, PathState& s, float t, const PixelSample& sample,
                         Rgb* radiance, RayCounters& rays) const;
    // Starts the next segment from a scattering vertex at `position`, direction sampled with
    // density `pdf`; Russian roulette. False when the path ends.
    bool continuePath(PathState& s, const Ray& next, const Vec3& position, float pdf, bool specular,
                      const PixelSample& sample, RayCounters& rays) const;

    // Next-event estimates, MIS-weighted against BSDF or phase sampling.
    Rgb sampleLight(const Scene& scene, const SurfaceHit& hit, const Material& material,
                    const ShadingContext& ctx, const Frame& frame, const Vec3& wo,
                    const Medium* medium, const PixelSample& sample, uint32_t vertex,
                    RayCounters& rays) const;
    Rgb sampleLightInMedium(const Scene& scene, const Vec3& position, float time,
                            const Medium& medium, const Vec3& wo, const PixelSample& sample,
                            uint32_t vertex, RayCounters& rays) const;
    // Picks a light and a point on it for next-event estimation from `position`.
    bool pickLight(const Scene& scene, const Vec3& position, float time, const PixelSample& sample,
                   uint32_t vertex, LightSample* ls, float* lightPdf, bool* infinite) const;
    // What reaches the end of a shadow ray that starts in `medium`: 0 or 1 without media, else
    // the transmittance; `*survival` is the free-flight survival probability for MIS.
    Rgb visibility(const Scene& scene, const Ray& shadow, const Medium* medium, bool infinite,
                   float* survival, RayCounters& rays) const;

    PathSettings settings_;
    bool nee_;
};

}  // namespace rr
