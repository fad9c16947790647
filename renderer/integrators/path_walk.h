// One path of one pixel sample for the path tracers (path_tracer.h describes the estimator):
// what the path carries from vertex to vertex, and the steps that extend it.
//
// Three choices keep every scene and technique from paying for what it does not use:
//  - kMedia (compile time): without media no free flights, boundary checks or medium tracking
//    exist, and shadow rays are plain occlusion queries;
//  - Guide (compile time): how the path's decisions are made (standard_sampling.h).
//    StandardSampling compiles away; a technique that steers decisions supplies its own guide,
//    and the walk then uses its densities everywhere, in MIS weights included;
//  - the direct-lighting estimator (run time) that makes next-event estimation at every
//    non-specular vertex, and which decides how the emission the path itself finds counts.
//
// Its functions are templates defined here so the compiler can inline the steps into run();
// PathTracer (path_tracer.h) runs it, and so can a technique's own integrator (TAIS).
#pragma once

#include <algorithm>
#include <limits>

#include "integrators/light_sample_estimator.h"
#include "integrators/medium_tracking.h"
#include "integrators/path_settings.h"
#include "integrators/scattering_vertex.h"
#include "integrators/standard_sampling.h"

namespace rr {

template <bool kMedia, PathGuide Guide>
class PathWalk {
  public:
    // `weight`: the camera ray's sampling weight (1 unless a guide warped the camera's
    // decisions).
    // `pixel`: the pixel's records, which the first vertex's estimate may keep.
    PathWalk(const Scene& scene, Guide& guide, RayCounters& rays, const PathSettings& settings,
             const DirectLightingEstimator& nee, const Ray& cameraRay, float weight = 1,
             PixelRecordSlot pixel = {})
        : scene_(scene),
          guide_(guide),
          sample_(guide.sample()),
          rays_(rays),
          maxDepth_(settings.maxDepth < 0 ? PathSettings::kDepthCap : settings.maxDepth),
          rrDepth_(settings.rrDepth),
          rrSurvival_(settings.rrSurvival),
          rrThreshold_(settings.rrThreshold),
          nee_(nee),
          pixel_(pixel),
          ray_(cameraRay),
          medium_(scene.medium()),
          throughput_(weight) {}

    Rgb run();

  private:
    static constexpr float kInfinity = std::numeric_limits<float>::infinity();

    uint32_t vertex() const { return static_cast<uint32_t>(depth_); }
    // The vertex the current ray left (the one whose decisions found what it hits).
    uint32_t previousVertex() const { return static_cast<uint32_t>(depth_ - 1); }

    // Free flight along the ray up to `tMax` in the current medium: true with the collision
    // distance in `*t`, false when the flight passes (the throughput updated either way).
    bool flyThroughMedium(float tMax, float* t);
    // Emission of the shape at `hit` times the throughput, MIS-weighted against next-event
    // estimation.
    Rgb emission(const SurfaceHit& hit) const;
    // Continues the ray through an index-matched boundary into the medium beyond.
    bool passThroughBoundary(const SurfaceHit& hit);
    // A surface vertex: next-event estimation and BSDF sampling. False when the path ends.
    bool scatterAtSurface(const SurfaceHit& hit);
    // A medium vertex at distance `t` along the ray: next-event estimation and phase
    // sampling. False when the path ends.
    bool scatterInMedium(float t);
    // Starts the next segment from the scattering vertex `from`, its direction sampled
    // with density `pdf`; Russian roulette. False when the path ends.
    bool continuePath(const Ray& next, const LightReference& from, float pdf, bool specular);

    // Next-event estimation at the vertex `point`, if the estimator samples lights.
    template <class Point>
    void estimateDirectLight(Point&& point);
    // Where a vertex's next-event estimate goes.
    VertexOutput<Guide> output() {
        return {guide_,    vertex(), throughput_,
                radiance_, rays_,    depth_ == 0 ? pixel_ : PixelRecordSlot{}};
    }
    // The weight of emission the path finds against next-event estimation from the previous
    // vertex, whose light sampling picks the same point with density lightPdf().
    template <class LightPdf>
    float foundEmissionWeight(const LightPdf& lightPdf) const {
        return rr::foundEmissionWeight(nee_, inFull_, 1.0f, scatterPdf_, lightPdf);
    }

    const Scene& scene_;
    Guide& guide_;
    const PixelSample& sample_;
    RayCounters& rays_;
    const int maxDepth_, rrDepth_;
    const float rrSurvival_;   // 0: throughput-driven
    const float rrThreshold_;  // throughput-driven roulette only below this survival
    const DirectLightingEstimator& nee_;
    const PixelRecordSlot pixel_;

    Ray ray_;
    const Medium* medium_;  // the medium the ray travels through (nullptr: vacuum)
    Rgb radiance_ = Rgb(0.0f);
    Rgb throughput_;
    // Product of η² over the refractions so far: radiance is scaled by 1/η² entering a denser
    // medium and back on leaving, which must not make Russian roulette kill paths inside glass
    // whose final weight is 1 (pbrt-v4's etaScale).
    float etaScale_ = 1;
    // The ray comes from the camera or a specular bounce: what it finds counts in full.
    bool inFull_ = true;
    // Density of the last direction sample (BSDF or phase function) times the free-flight
    // survival probability of the media crossed since: the density with which this strategy
    // finds the light the path hits, for MIS.
    float scatterPdf_ = 0;
    LightReference previous_{Vec3(0.0f)};  // the last scattering vertex, for MIS
    int depth_ = 0;                        // scattering events so far: the index of the next vertex
    int crossings_ = 0;                    // index-matched boundaries passed
    // The current ray's free-flight survival budget (medium.h); 0 until drawn.
    float flightBudget_ = 0;
};

template <bool kMedia, PathGuide Guide>
Rgb PathWalk<kMedia, Guide>::run() {
    for (;;) {
        SurfaceHit hit;
        const bool found = scene_.intersect(ray_, &hit);
        if constexpr (kMedia) {
            float t;
            if (medium_ && flyThroughMedium(found ? hit.distance : kInfinity, &t)) {
                if (!scatterInMedium(t)) break;
                continue;
            }
        }
        if (!found) {
            radiance_ +=
                throughput_ * escapedRadiance(scene_, ray_.direction, [this](const Light& l) {
                    return foundEmissionWeight([&] {
                        return guide_.lightPdf(previousVertex(), l, previous_, ray_.direction);
                    });
                });
            break;
        }
        if (hit.shape->areaLight()) radiance_ += emission(hit);
        if (kMedia && hit.shape->isMediumBoundary()) {
            if (!passThroughBoundary(hit)) break;
            continue;
        }
        if (!scatterAtSurface(hit)) break;
    }
    return radiance_;
}

template <bool kMedia, PathGuide Guide>
bool PathWalk<kMedia, Guide>::flyThroughMedium(float tMax, float* t) {
    if (flightBudget_ == 0) {
        float warpPdf;
        flightBudget_ = 1.0f - guide_.flightCoordinate(vertex(), radiance_, &warpPdf);
        throughput_ *= 1.0f / warpPdf;
    }
    const FreeFlight flight = medium_->sampleFreeFlight(flightBudget_, tMax);
    throughput_ *= flight.weight;
    if (flight.collided) {
        *t = flight.distance;
        return true;
    }
    flightBudget_ = flight.budgetLeft;
    scatterPdf_ *= flight.survival;
    return false;
}

template <bool kMedia, PathGuide Guide>
Rgb PathWalk<kMedia, Guide>::emission(const SurfaceHit& hit) const {
    const AreaLight* light = hit.shape->areaLight();
    const Rgb le = light->emitted(hit.geometricNormal, -ray_.direction);
    if (le.isBlack()) return le;
    return throughput_ * le * foundEmissionWeight([&] {
               return guide_.lightPdf(previousVertex(), *light, previous_, hit);
           });
}

template <bool kMedia, PathGuide Guide>
bool PathWalk<kMedia, Guide>::passThroughBoundary(const SurfaceHit& hit) {
    if (++crossings_ > kMaxBoundaryCrossings) return false;
    medium_ = mediumOnSide(scene_, hit, ray_.direction, medium_);
    ray_ = hit.spawn(ray_.direction);
    ++rays_.extension;
    return true;
}

template <bool kMedia, PathGuide Guide>
bool PathWalk<kMedia, Guide>::scatterAtSurface(const SurfaceHit& hit) {
    const Material* material = hit.shape->material();
    if (depth_ >= maxDepth_ || !material) return false;

    const Frame frame = hit.shadingFrame();
    const Vec3 wo = frame.toLocal(-ray_.direction);
    const ShadingContext ctx{hit.uv, hit.position};
    if (material->hasNonSpecular())
        estimateDirectLight(
            SurfaceVertex<kMedia, Guide>(output(), hit, *material, ctx, frame, wo, medium_, 1.0f));

    BsdfSample bs;
    if (!guide_.sampleBsdf(vertex(), *material, ctx, frame, wo, radiance_, &bs)) return false;
    throughput_ *= bs.weight;
    etaScale_ *= bs.eta * bs.eta;
    if (throughput_.isBlack()) return false;
    const Vec3 wi = frame.toWorld(bs.wi);
    if constexpr (kMedia) medium_ = mediumOnSide(scene_, hit, wi, medium_);
    return continuePath(hit.spawn(wi), {hit.position, frame.n}, bs.pdf, bs.isSpecular());
}

template <bool kMedia, PathGuide Guide>
bool PathWalk<kMedia, Guide>::scatterInMedium(float t) {
    if (depth_ >= maxDepth_ || throughput_.isBlack()) return false;
    const Vec3 position = ray_.origin + ray_.direction * t;
    const Vec3 wo = -ray_.direction;
    estimateDirectLight(MediumVertex<Guide>(output(), position, ray_.time, wo, *medium_));
    // Exact sampling: the weight p/pdf is 1 and the throughput is unchanged.
    Vec3 wi;
    const float pdf = guide_.samplePhase(vertex(), medium_->phase(), wo, &wi);
    if (!(pdf > 0)) return false;
    return continuePath(Ray{position, wi, kInfinity, ray_.time}, position, pdf,
                        /*specular=*/false);
}

template <bool kMedia, PathGuide Guide>
bool PathWalk<kMedia, Guide>::continuePath(const Ray& next, const LightReference& from, float pdf,
                                           bool specular) {
    inFull_ = specular;
    scatterPdf_ = pdf;
    previous_ = from;
    ray_ = next;
    flightBudget_ = 0;
    if (depth_ + 1 >= rrDepth_) {
        const float survive =
            rrSurvival_ > 0 ? rrSurvival_ : std::min(1.0f, throughput_.maxComponent() * etaScale_);
        // The draw is indexed by its decision and vertex, so skipping it changes no other.
        if (survive < rrThreshold_ || rrSurvival_ > 0) {
            if (sample_.get1D(Decision::RussianRoulette, vertex()) >= survive) return false;
            throughput_ *= 1.0f / survive;
        }
    }
    ++depth_;
    ++rays_.extension;
    return true;
}

template <bool kMedia, PathGuide Guide>
template <class Point>
void PathWalk<kMedia, Guide>::estimateDirectLight(Point&& point) {
    if (nee_.lightSamples() > 0) runEstimator(nee_, point);
}

// One path of pixel (x, y), its camera ray from `guide`, through the walk compiled with or
// without media as the scene needs.
template <PathGuide Guide>
Rgb tracePath(const Scene& scene, Guide& guide, int x, int y, const PathSettings& settings,
              const DirectLightingEstimator& nee, RayCounters& rays, PixelRecordSlot pixel = {}) {
    float weight;
    const Ray ray = guide.cameraRay(x, y, &weight);
    ++rays.camera;
    if (scene.hasMedia())
        return PathWalk<true, Guide>(scene, guide, rays, settings, nee, ray, weight, pixel).run();
    return PathWalk<false, Guide>(scene, guide, rays, settings, nee, ray, weight, pixel).run();
}

}  // namespace rr
