#include "integrators/path_tracer.h"

#include <algorithm>
#include <limits>

#include "integrators/medium_tracking.h"
#include "scene/lights/area_light.h"

namespace rr {

// What a path carries from one vertex to the next.
struct PathTracer::PathState {
    PathState(const Ray& cameraRay, const Medium* sceneMedium)
        : ray(cameraRay), medium(sceneMedium) {}

    Ray ray;
    const Medium* medium;  // the medium the ray travels through (nullptr: vacuum)
    Rgb throughput = Rgb(1.0f);
    // Product of η² over the refractions so far: radiance is scaled by 1/η² entering a denser
    // medium and back on leaving, which must not make Russian roulette kill paths inside glass
    // whose final weight is 1 (pbrt-v4's etaScale).
    float etaScale = 1;
    bool countEmission = true;  // camera ray, or a specular bounce, or BSDF-only tracing
    // Density of the path's last direction sample (BSDF or phase function), times the
    // free-flight survival probability of the media crossed since: the density with which
    // this strategy finds the light the path hits, for MIS.
    float scatterPdf = 0;
    Vec3 previous;      // the last scattering vertex
    int depth = 0;      // scattering events so far: the index of the next vertex
    int crossings = 0;  // index-matched boundaries passed
    // Free-flight survival budget of the current ray (medium.h); 0 until drawn.
    float flightBudget = 0;
};

nlohmann::json PathTracer::parameters() const {
    return {{"type", name()}, {"max_depth", settings_.maxDepth}, {"rr_depth", settings_.rrDepth}};
}

Rgb PathTracer::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const {
    PathState s(generateCameraRay(scene.camera(), x, y, sample), scene.medium());
    ++rays.camera;
    Rgb radiance(0.0f);
    for (;;) {
        SurfaceHit hit;
        const bool found = scene.intersect(s.ray, &hit);
        float t;
        if (s.medium &&
            flyThroughMedium(s, found ? hit.distance : std::numeric_limits<float>::infinity(),
                             sample, &t)) {
            if (!scatterInMedium(scene, s, t, sample, &radiance, rays)) break;
            continue;
        }
        if (!found) {
            radiance += s.throughput * escapedRadiance(scene, s.ray.direction, s.previous,
                                                       s.countEmission, s.scatterPdf);
            break;
        }
        if (hit.shape->areaLight()) radiance += emission(scene, s, hit);
        if (hit.shape->isMediumBoundary()) {
            if (!passThroughBoundary(scene, s, hit, rays)) break;
            continue;
        }
        if (!scatterAtSurface(scene, s, hit, sample, &radiance, rays)) break;
    }
    return radiance;
}

bool PathTracer::flyThroughMedium(PathState& s, float tMax, const PixelSample& sample,
                                  float* t) const {
    if (s.flightBudget == 0)
        s.flightBudget =
            1.0f - sample.get1D(Decision::MediumDistance, static_cast<uint32_t>(s.depth));
    const FreeFlight flight = s.medium->sampleFreeFlight(s.flightBudget, tMax);
    s.throughput *= flight.weight;
    if (flight.collided) {
        *t = flight.distance;
        return true;
    }
    s.flightBudget = flight.budgetLeft;
    s.scatterPdf *= flight.survival;
    return false;
}

Rgb PathTracer::emission(const Scene& scene, const PathState& s, const SurfaceHit& hit) const {
    const AreaLight* light = hit.shape->areaLight();
    const Rgb le = light->emitted(hit.geometricNormal, -s.ray.direction);
    if (le.isBlack()) return le;
    const float lightPdf = s.countEmission ? 0.0f
                                           : scene.lightSelector().pmf(*light, s.previous) *
                                                 light->pdf(s.previous, hit);
    return s.throughput * le * emissionMisWeight(s.countEmission, s.scatterPdf, lightPdf);
}

bool PathTracer::passThroughBoundary(const Scene& scene, PathState& s, const SurfaceHit& hit,
                                     RayCounters& rays) const {
    if (++s.crossings > kMaxBoundaryCrossings) return false;
    s.medium = mediumOnSide(scene, hit, s.ray.direction, s.medium);
    s.ray = hit.spawn(s.ray.direction);
    ++rays.extension;
    return true;
}

bool PathTracer::scatterAtSurface(const Scene& scene, PathState& s, const SurfaceHit& hit,
                                  const PixelSample& sample, Rgb* radiance,
                                  RayCounters& rays) const {
    const Material* material = hit.shape->material();
    if (s.depth >= maxDepth() || !material) return false;

    const uint32_t vertex = static_cast<uint32_t>(s.depth);
    const Frame frame = hit.shadingFrame();
    const Vec3 wo = frame.toLocal(-s.ray.direction);
    const ShadingContext ctx{hit.uv, hit.position};
    if (nee_ && material->hasNonSpecular())
        *radiance += s.throughput * sampleLight(scene, hit, *material, ctx, frame, wo, s.medium,
                                                sample, vertex, rays);

    BsdfSample bs;
    if (!material->sample(ctx, wo, sample.get1D(Decision::BsdfLobe, vertex),
                          sample.get2D(Decision::BsdfDirection, vertex), &bs))
        return false;
    s.throughput *= bs.weight;
    s.etaScale *= bs.eta * bs.eta;
    if (s.throughput.isBlack()) return false;
    const Vec3 wi = frame.toWorld(bs.wi);
    s.medium = mediumOnSide(scene, hit, wi, s.medium);
    return continuePath(s, hit.spawn(wi), hit.position, bs.pdf, bs.isSpecular(), sample, rays);
}

bool PathTracer::scatterInMedium(const Scene& scene, PathState& s, float t,
                                 const PixelSample& sample, Rgb* radiance,
                                 RayCounters& rays) const {
    if (s.depth >= maxDepth() || s.throughput.isBlack()) return false;
    const uint32_t vertex = static_cast<uint32_t>(s.depth);
    const Vec3 position = s.ray.origin + s.ray.direction * t;
    const Vec3 wo = -s.ray.direction;
    if (nee_)
        *radiance += s.throughput * sampleLightInMedium(scene, position, s.ray.time, *s.medium, wo,
                                                        sample, vertex, rays);
    // Exact sampling: the weight p/pdf is 1 and the throughput is unchanged.
    Vec3 wi;
    const float pdf =
        s.medium->phase().sample(wo, sample.get2D(Decision::BsdfDirection, vertex), &wi);
    if (!(pdf > 0)) return false;
    const Ray next{position, wi, std::numeric_limits<float>::infinity(), s.ray.time};
    return continuePath(s, next, position, pdf, /*specular=*/false, sample, rays);
}

bool PathTracer::continuePath(PathState& s, const Ray& next, const Vec3& position, float pdf,
                              bool specular, const PixelSample& sample, RayCounters& rays) const {
    s.countEmission = !nee_ || specular;
    s.scatterPdf = pdf;
    s.previous = position;
    s.ray = next;
    s.flightBudget = 0;
    if (s.depth + 1 >= settings_.rrDepth) {
        const float survive = std::min(1.0f, s.throughput.maxComponent() * s.etaScale);
        if (sample.get1D(Decision::RussianRoulette, static_cast<uint32_t>(s.depth)) >= survive)
            return false;
        s.throughput *= 1.0f / survive;
    }
    ++s.depth;
    ++rays.extension;
    return true;
}

Rgb PathTracer::sampleLight(const Scene& scene, const SurfaceHit& hit, const Material& material,
                            const ShadingContext& ctx, const Frame& frame, const Vec3& wo,
                            const Medium* medium, const PixelSample& sample, uint32_t vertex,
                            RayCounters& rays) const {
    LightSample ls;
    float lightPdf;
    bool infinite;
    if (!pickLight(scene, hit.position, hit.time, sample, vertex, &ls, &lightPdf, &infinite))
        return Rgb(0.0f);
    const Vec3 wi = frame.toLocal(ls.direction);
    const Rgb f = material.eval(ctx, wo, wi);
    if (f.isBlack()) return Rgb(0.0f);
    float survival;
    const Rgb tr =
        visibility(scene, hit.spawnTo(ls.position, ls.normal, ls.errorScale),
                   mediumOnSide(scene, hit, ls.direction, medium), infinite, &survival, rays);
    if (tr.isBlack()) return Rgb(0.0f);
    const float weight =
        ls.isDelta ? 1.0f : powerHeuristic(1, lightPdf, 1, material.pdf(ctx, wo, wi) * survival);
    return f * ls.radiance * tr * (weight / lightPdf);
}

Rgb PathTracer::sampleLightInMedium(const Scene& scene, const Vec3& position, float time,
                                    const Medium& medium, const Vec3& wo, const PixelSample& sample,
                                    uint32_t vertex, RayCounters& rays) const {
    LightSample ls;
    float lightPdf;
    bool infinite;
    if (!pickLight(scene, position, time, sample, vertex, &ls, &lightPdf, &infinite))
        return Rgb(0.0f);
    const float p = medium.phase().eval(wo, ls.direction);
    if (!(p > 0)) return Rgb(0.0f);
    // A medium point lies on no surface: only the light's end of the shadow ray is lifted.
    const Vec3 target =
        offsetRayOrigin(ls.position, ls.normal, position - ls.position, ls.errorScale);
    const float distance = length(target - position);
    const Ray shadow{position, (target - position) / distance, distance, time};
    float survival;
    const Rgb tr = visibility(scene, shadow, &medium, infinite, &survival, rays);
    if (tr.isBlack()) return Rgb(0.0f);
    const float weight =
        ls.isDelta
            ? 1.0f
            : powerHeuristic(1, lightPdf, 1, medium.phase().pdf(wo, ls.direction) * survival);
    return ls.radiance * tr * (p * weight / lightPdf);
}

bool PathTracer::pickLight(const Scene& scene, const Vec3& position, float time,
                           const PixelSample& sample, uint32_t vertex, LightSample* ls,
                           float* lightPdf, bool* infinite) const {
    float selectPmf;
    const Light* light = scene.lightSelector().select(sample.get1D(Decision::LightSelect, vertex),
                                                      position, &selectPmf);
    if (!light || !light->sample(position, sample.get2D(Decision::LightPoint, vertex), time, ls))
        return false;
    *lightPdf = selectPmf * ls->pdf;
    *infinite = light->isInfinite();
    return true;
}

Rgb PathTracer::visibility(const Scene& scene, const Ray& shadow, const Medium* medium,
                           bool infinite, float* survival, RayCounters& rays) const {
    if (scene.features().media)
        return shadowTransmittance(scene, shadow, medium, infinite, survival, rays);
    // Without media: the occlusion query alone.
    *survival = 1;
    ++rays.shadow;
    return Rgb(scene.occluded(shadow) ? 0.0f : 1.0f);
}

}  // namespace rr
