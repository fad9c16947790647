// One path of one pixel sample for the path tracers (path_tracer.h describes the estimator):
// what the path carries from vertex to vertex, and the steps that extend it.
//
// Two compile-time choices keep every scene and technique from paying for what it does not use:
//  - kMedia: without media no free flights, boundary checks or medium tracking exist, and
//    shadow rays are plain occlusion queries;
//  - Guide: how the path's decisions are made. StandardSampling (below) is plain importance
//    sampling — light selection, light sampling, BSDF sampling — and compiles away entirely;
//    a technique that steers decisions (TAIS's importance maps) supplies its own class with the
//    same members, and the walk then uses its densities everywhere, in MIS weights included.
//
// The header is included only by the files that instantiate the walk; its functions are
// templates defined here so the compiler can inline the steps into run().
#pragma once

#include <algorithm>
#include <limits>

#include "integrators/integrator.h"
#include "integrators/medium_tracking.h"
#include "integrators/path_tracer.h"
#include "scene/lights/area_light.h"

namespace rr {

// Standard importance sampling for every decision of a path (what `path` and `path_mis` do).
// `vertex` is the index of the scattering vertex that makes the decision (0: the first one
// the camera ray reaches); `radiance` is what the path has gathered before the decision, so a
// guide can credit a decision with what follows it.
class StandardSampling {
  public:
    StandardSampling(const Scene& scene, const PixelSample& sample)
        : scene_(scene), sample_(sample) {}

    // The coordinate of the free flight of the segment that leads to `vertex` (the camera
    // ray's for vertex 0), and the density of any warp applied to it.
    float flightCoordinate(uint32_t vertex, const Rgb& /*radiance*/, float* warpPdf) {
        *warpPdf = 1;
        return sample_.get1D(Decision::MediumDistance, vertex);
    }
    // Next-event estimation's light and the point on it, with the density of the pair.
    bool sampleLight(uint32_t vertex, const Vec3& reference, float time, LightSample* ls,
                     float* pdf, const Light** chosen) {
        float selectPmf;
        const Light* light = scene_.lightSelector().select(
            sample_.get1D(Decision::LightSelect, vertex), reference, &selectPmf);
        if (!light ||
            !light->sample(reference, sample_.get2D(Decision::LightPoint, vertex), time, ls))
            return false;
        *pdf = selectPmf * ls->pdf;
        *chosen = light;
        return true;
    }
    // The light sample's contribution (already weighted) to the path's radiance.
    void lightContribution(uint32_t /*vertex*/, const Rgb& /*contribution*/) {}
    // Density with which sampleLight() at `vertex` picks `light` and its point `hit`.
    float lightPdf(uint32_t vertex, const AreaLight& light, const Vec3& reference,
                   const SurfaceHit& hit) const {
        (void)vertex;
        return scene_.lightSelector().pmf(light, reference) * light.pdf(reference, hit);
    }
    // The same for an infinite light seen in direction `w`.
    float lightPdf(uint32_t vertex, const Light& light, const Vec3& reference,
                   const Vec3& w) const {
        (void)vertex;
        return scene_.lightSelector().pmf(light, reference) * light.directionPdf(w);
    }
    // The surface scattering decision (lobe, then direction) at `vertex`.
    bool sampleBsdf(uint32_t vertex, const Material& material, const ShadingContext& ctx,
                    const Frame& /*frame*/, const Vec3& wo, const Rgb& /*radiance*/,
                    BsdfSample* bs) {
        return material.sample(ctx, wo, sample_.get1D(Decision::BsdfLobe, vertex),
                               sample_.get2D(Decision::BsdfDirection, vertex), bs);
    }
    // Density with which sampleBsdf() at `vertex` yields the local direction `wi`.
    float bsdfPdf(uint32_t /*vertex*/, const Material& material, const ShadingContext& ctx,
                  const Frame& /*frame*/, const Vec3& wo, const Vec3& wi) const {
        return material.pdf(ctx, wo, wi);
    }

    const PixelSample& sample() const { return sample_; }

  private:
    const Scene& scene_;
    const PixelSample& sample_;
};

template <bool kMedia, class Guide>
class PathWalk {
  public:
    // `weight`: the camera ray's sampling weight (1 unless a guide warped the camera's
    // decisions).
    PathWalk(const Scene& scene, Guide& guide, RayCounters& rays, const PathSettings& settings,
             bool nee, const Ray& cameraRay, float weight = 1)
        : scene_(scene),
          guide_(guide),
          sample_(guide.sample()),
          rays_(rays),
          maxDepth_(settings.maxDepth < 0 ? PathTracer::kDepthCap : settings.maxDepth),
          rrDepth_(settings.rrDepth),
          nee_(nee),
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
    // Starts the next segment from the scattering vertex at `position`, its direction sampled
    // with density `pdf`; Russian roulette. False when the path ends.
    bool continuePath(const Ray& next, const Vec3& position, float pdf, bool specular);

    // Next-event estimates, MIS-weighted against BSDF or phase sampling.
    Rgb sampleLight(const SurfaceHit& hit, const Material& material, const ShadingContext& ctx,
                    const Frame& frame, const Vec3& wo);
    Rgb sampleLightInMedium(const Vec3& position, const Vec3& wo);
    // What reaches the end of a shadow ray that starts in `medium`: the transmittance (0 or 1
    // without media); `*survival` is the free-flight survival probability, for MIS.
    Rgb visibility(const Ray& shadow, const Medium* medium, bool infinite, float* survival) const;

    const Scene& scene_;
    Guide& guide_;
    const PixelSample& sample_;
    RayCounters& rays_;
    const int maxDepth_, rrDepth_;
    const bool nee_;

    Ray ray_;
    const Medium* medium_;  // the medium the ray travels through (nullptr: vacuum)
    Rgb radiance_ = Rgb(0.0f);
    Rgb throughput_;
    // Product of η² over the refractions so far: radiance is scaled by 1/η² entering a denser
    // medium and back on leaving, which must not make Russian roulette kill paths inside glass
    // whose final weight is 1 (pbrt-v4's etaScale).
    float etaScale_ = 1;
    bool countEmission_ = true;  // camera ray, or a specular bounce, or BSDF-only tracing
    // Density of the last direction sample (BSDF or phase function) times the free-flight
    // survival probability of the media crossed since: the density with which this strategy
    // finds the light the path hits, for MIS.
    float scatterPdf_ = 0;
    Vec3 previous_;      // the last scattering vertex
    int depth_ = 0;      // scattering events so far: the index of the next vertex
    int crossings_ = 0;  // index-matched boundaries passed
    // The current ray's free-flight survival budget (medium.h); 0 until drawn.
    float flightBudget_ = 0;
};

template <bool kMedia, class Guide>
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
                throughput_ * escapedRadiance(scene_, ray_.direction, countEmission_, scatterPdf_,
                                              [this](const Light& light) {
                                                  return guide_.lightPdf(previousVertex(), light,
                                                                         previous_, ray_.direction);
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

template <bool kMedia, class Guide>
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

template <bool kMedia, class Guide>
Rgb PathWalk<kMedia, Guide>::emission(const SurfaceHit& hit) const {
    const AreaLight* light = hit.shape->areaLight();
    const Rgb le = light->emitted(hit.geometricNormal, -ray_.direction);
    if (le.isBlack()) return le;
    const float lightPdf =
        countEmission_ ? 0.0f : guide_.lightPdf(previousVertex(), *light, previous_, hit);
    return throughput_ * le * emissionMisWeight(countEmission_, scatterPdf_, lightPdf);
}

template <bool kMedia, class Guide>
bool PathWalk<kMedia, Guide>::passThroughBoundary(const SurfaceHit& hit) {
    if (++crossings_ > kMaxBoundaryCrossings) return false;
    medium_ = mediumOnSide(scene_, hit, ray_.direction, medium_);
    ray_ = hit.spawn(ray_.direction);
    ++rays_.extension;
    return true;
}

template <bool kMedia, class Guide>
bool PathWalk<kMedia, Guide>::scatterAtSurface(const SurfaceHit& hit) {
    const Material* material = hit.shape->material();
    if (depth_ >= maxDepth_ || !material) return false;

    const Frame frame = hit.shadingFrame();
    const Vec3 wo = frame.toLocal(-ray_.direction);
    const ShadingContext ctx{hit.uv, hit.position};
    if (nee_ && material->hasNonSpecular())
        radiance_ += throughput_ * sampleLight(hit, *material, ctx, frame, wo);

    BsdfSample bs;
    if (!guide_.sampleBsdf(vertex(), *material, ctx, frame, wo, radiance_, &bs)) return false;
    throughput_ *= bs.weight;
    etaScale_ *= bs.eta * bs.eta;
    if (throughput_.isBlack()) return false;
    const Vec3 wi = frame.toWorld(bs.wi);
    if constexpr (kMedia) medium_ = mediumOnSide(scene_, hit, wi, medium_);
    return continuePath(hit.spawn(wi), hit.position, bs.pdf, bs.isSpecular());
}

template <bool kMedia, class Guide>
bool PathWalk<kMedia, Guide>::scatterInMedium(float t) {
    if (depth_ >= maxDepth_ || throughput_.isBlack()) return false;
    const Vec3 position = ray_.origin + ray_.direction * t;
    const Vec3 wo = -ray_.direction;
    if (nee_) radiance_ += throughput_ * sampleLightInMedium(position, wo);
    // Exact sampling: the weight p/pdf is 1 and the throughput is unchanged.
    Vec3 wi;
    const float pdf =
        medium_->phase().sample(wo, sample_.get2D(Decision::BsdfDirection, vertex()), &wi);
    if (!(pdf > 0)) return false;
    return continuePath(Ray{position, wi, kInfinity, ray_.time}, position, pdf,
                        /*specular=*/false);
}

template <bool kMedia, class Guide>
bool PathWalk<kMedia, Guide>::continuePath(const Ray& next, const Vec3& position, float pdf,
                                           bool specular) {
    countEmission_ = !nee_ || specular;
    scatterPdf_ = pdf;
    previous_ = position;
    ray_ = next;
    flightBudget_ = 0;
    if (depth_ + 1 >= rrDepth_) {
        const float survive = std::min(1.0f, throughput_.maxComponent() * etaScale_);
        if (sample_.get1D(Decision::RussianRoulette, vertex()) >= survive) return false;
        throughput_ *= 1.0f / survive;
    }
    ++depth_;
    ++rays_.extension;
    return true;
}

template <bool kMedia, class Guide>
Rgb PathWalk<kMedia, Guide>::sampleLight(const SurfaceHit& hit, const Material& material,
                                         const ShadingContext& ctx, const Frame& frame,
                                         const Vec3& wo) {
    LightSample ls;
    float lightPdf;
    const Light* light;
    if (!guide_.sampleLight(vertex(), hit.position, hit.time, &ls, &lightPdf, &light))
        return Rgb(0.0f);
    const Vec3 wi = frame.toLocal(ls.direction);
    const Rgb f = material.eval(ctx, wo, wi);
    if (f.isBlack()) return Rgb(0.0f);
    float survival;
    const Medium* medium = kMedia ? mediumOnSide(scene_, hit, ls.direction, medium_) : nullptr;
    const Rgb tr = visibility(hit.spawnTo(ls.position, ls.normal, ls.errorScale), medium,
                              light->isInfinite(), &survival);
    if (tr.isBlack()) return Rgb(0.0f);
    const float weight =
        ls.isDelta
            ? 1.0f
            : powerHeuristic(1, lightPdf, 1,
                             guide_.bsdfPdf(vertex(), material, ctx, frame, wo, wi) * survival);
    const Rgb contribution = f * ls.radiance * tr * (weight / lightPdf);
    guide_.lightContribution(vertex(), throughput_ * contribution);
    return contribution;
}

template <bool kMedia, class Guide>
Rgb PathWalk<kMedia, Guide>::sampleLightInMedium(const Vec3& position, const Vec3& wo) {
    LightSample ls;
    float lightPdf;
    const Light* light;
    if (!guide_.sampleLight(vertex(), position, ray_.time, &ls, &lightPdf, &light))
        return Rgb(0.0f);
    const PhaseFunction& phase = medium_->phase();
    const float p = phase.eval(wo, ls.direction);
    if (!(p > 0)) return Rgb(0.0f);
    // A medium point lies on no surface: only the light's end of the shadow ray is lifted.
    const Vec3 target =
        offsetRayOrigin(ls.position, ls.normal, position - ls.position, ls.errorScale);
    const float distance = length(target - position);
    const Ray shadow{position, (target - position) / distance, distance, ray_.time};
    float survival;
    const Rgb tr = visibility(shadow, medium_, light->isInfinite(), &survival);
    if (tr.isBlack()) return Rgb(0.0f);
    const float weight =
        ls.isDelta ? 1.0f : powerHeuristic(1, lightPdf, 1, phase.pdf(wo, ls.direction) * survival);
    const Rgb contribution = ls.radiance * tr * (p * weight / lightPdf);
    guide_.lightContribution(vertex(), throughput_ * contribution);
    return contribution;
}

template <bool kMedia, class Guide>
Rgb PathWalk<kMedia, Guide>::visibility(const Ray& shadow, const Medium* medium, bool infinite,
                                        float* survival) const {
    if constexpr (kMedia) {
        return shadowTransmittance(scene_, shadow, medium, infinite, survival, rays_);
    } else {
        *survival = 1;
        ++rays_.shadow;
        return Rgb(scene_.occluded(shadow) ? 0.0f : 1.0f);
    }
}

}  // namespace rr
