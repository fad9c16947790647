#include "integrators/path_tracer.h"

#include <algorithm>
#include <limits>

#include "integrators/medium_tracking.h"
#include "scene/lights/area_light.h"

namespace rr {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// One path of one pixel sample: what it carries from vertex to vertex, and the steps that
// extend it. Scenes without media pay nothing for them: the walk is compiled twice, and with
// kMedia = false no media code exists (no free flights, boundary checks or medium tracking,
// and shadow rays are plain occlusion queries). Internal linkage lets the compiler inline the
// steps into run() and keep the state in registers.
template <bool kMedia>
class PathWalk {
  public:
    PathWalk(const Scene& scene, const PixelSample& sample, RayCounters& rays,
             const PathSettings& settings, bool nee, const Ray& cameraRay)
        : scene_(scene),
          sample_(sample),
          rays_(rays),
          maxDepth_(settings.maxDepth < 0 ? PathTracer::kDepthCap : settings.maxDepth),
          rrDepth_(settings.rrDepth),
          nee_(nee),
          ray_(cameraRay),
          medium_(scene.medium()) {}

    Rgb run();

  private:
    uint32_t vertex() const { return static_cast<uint32_t>(depth_); }

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
                    const Frame& frame, const Vec3& wo) const;
    Rgb sampleLightInMedium(const Vec3& position, const Vec3& wo) const;
    // Picks a light and a point on it from `position` (the vertex's LightSelect and
    // LightPoint decisions).
    bool pickLight(const Vec3& position, float time, LightSample* ls, float* lightPdf,
                   bool* infinite) const;
    // What reaches the end of a shadow ray that starts in `medium`: the transmittance (0 or 1
    // without media); `*survival` is the free-flight survival probability, for MIS.
    Rgb visibility(const Ray& shadow, const Medium* medium, bool infinite, float* survival) const;

    const Scene& scene_;
    const PixelSample& sample_;
    RayCounters& rays_;
    const int maxDepth_, rrDepth_;
    const bool nee_;

    Ray ray_;
    const Medium* medium_;  // the medium the ray travels through (nullptr: vacuum)
    Rgb radiance_ = Rgb(0.0f);
    Rgb throughput_ = Rgb(1.0f);
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

template <bool kMedia>
Rgb PathWalk<kMedia>::run() {
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
            radiance_ += throughput_ * escapedRadiance(scene_, ray_.direction, previous_,
                                                       countEmission_, scatterPdf_);
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

template <bool kMedia>
bool PathWalk<kMedia>::flyThroughMedium(float tMax, float* t) {
    if (flightBudget_ == 0)
        flightBudget_ = 1.0f - sample_.get1D(Decision::MediumDistance, vertex());
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

template <bool kMedia>
Rgb PathWalk<kMedia>::emission(const SurfaceHit& hit) const {
    const AreaLight* light = hit.shape->areaLight();
    const Rgb le = light->emitted(hit.geometricNormal, -ray_.direction);
    if (le.isBlack()) return le;
    const float lightPdf =
        countEmission_ ? 0.0f
                       : scene_.lightSelector().pmf(*light, previous_) * light->pdf(previous_, hit);
    return throughput_ * le * emissionMisWeight(countEmission_, scatterPdf_, lightPdf);
}

template <bool kMedia>
bool PathWalk<kMedia>::passThroughBoundary(const SurfaceHit& hit) {
    if (++crossings_ > kMaxBoundaryCrossings) return false;
    medium_ = mediumOnSide(scene_, hit, ray_.direction, medium_);
    ray_ = hit.spawn(ray_.direction);
    ++rays_.extension;
    return true;
}

template <bool kMedia>
bool PathWalk<kMedia>::scatterAtSurface(const SurfaceHit& hit) {
    const Material* material = hit.shape->material();
    if (depth_ >= maxDepth_ || !material) return false;

    const Frame frame = hit.shadingFrame();
    const Vec3 wo = frame.toLocal(-ray_.direction);
    const ShadingContext ctx{hit.uv, hit.position};
    if (nee_ && material->hasNonSpecular())
        radiance_ += throughput_ * sampleLight(hit, *material, ctx, frame, wo);

    BsdfSample bs;
    if (!material->sample(ctx, wo, sample_.get1D(Decision::BsdfLobe, vertex()),
                          sample_.get2D(Decision::BsdfDirection, vertex()), &bs))
        return false;
    throughput_ *= bs.weight;
    etaScale_ *= bs.eta * bs.eta;
    if (throughput_.isBlack()) return false;
    const Vec3 wi = frame.toWorld(bs.wi);
    if constexpr (kMedia) medium_ = mediumOnSide(scene_, hit, wi, medium_);
    return continuePath(hit.spawn(wi), hit.position, bs.pdf, bs.isSpecular());
}

template <bool kMedia>
bool PathWalk<kMedia>::scatterInMedium(float t) {
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

template <bool kMedia>
bool PathWalk<kMedia>::continuePath(const Ray& next, const Vec3& position, float pdf,
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

template <bool kMedia>
Rgb PathWalk<kMedia>::sampleLight(const SurfaceHit& hit, const Material& material,
                                  const ShadingContext& ctx, const Frame& frame,
                                  const Vec3& wo) const {
    LightSample ls;
    float lightPdf;
    bool infinite;
    if (!pickLight(hit.position, hit.time, &ls, &lightPdf, &infinite)) return Rgb(0.0f);
    const Vec3 wi = frame.toLocal(ls.direction);
    const Rgb f = material.eval(ctx, wo, wi);
    if (f.isBlack()) return Rgb(0.0f);
    float survival;
    const Medium* medium = kMedia ? mediumOnSide(scene_, hit, ls.direction, medium_) : nullptr;
    const Rgb tr =
        visibility(hit.spawnTo(ls.position, ls.normal, ls.errorScale), medium, infinite, &survival);
    if (tr.isBlack()) return Rgb(0.0f);
    const float weight =
        ls.isDelta ? 1.0f : powerHeuristic(1, lightPdf, 1, material.pdf(ctx, wo, wi) * survival);
    return f * ls.radiance * tr * (weight / lightPdf);
}

template <bool kMedia>
Rgb PathWalk<kMedia>::sampleLightInMedium(const Vec3& position, const Vec3& wo) const {
    LightSample ls;
    float lightPdf;
    bool infinite;
    if (!pickLight(position, ray_.time, &ls, &lightPdf, &infinite)) return Rgb(0.0f);
    const PhaseFunction& phase = medium_->phase();
    const float p = phase.eval(wo, ls.direction);
    if (!(p > 0)) return Rgb(0.0f);
    // A medium point lies on no surface: only the light's end of the shadow ray is lifted.
    const Vec3 target =
        offsetRayOrigin(ls.position, ls.normal, position - ls.position, ls.errorScale);
    const float distance = length(target - position);
    const Ray shadow{position, (target - position) / distance, distance, ray_.time};
    float survival;
    const Rgb tr = visibility(shadow, medium_, infinite, &survival);
    if (tr.isBlack()) return Rgb(0.0f);
    const float weight =
        ls.isDelta ? 1.0f : powerHeuristic(1, lightPdf, 1, phase.pdf(wo, ls.direction) * survival);
    return ls.radiance * tr * (p * weight / lightPdf);
}

template <bool kMedia>
bool PathWalk<kMedia>::pickLight(const Vec3& position, float time, LightSample* ls, float* lightPdf,
                                 bool* infinite) const {
    float selectPmf;
    const Light* light = scene_.lightSelector().select(
        sample_.get1D(Decision::LightSelect, vertex()), position, &selectPmf);
    if (!light || !light->sample(position, sample_.get2D(Decision::LightPoint, vertex()), time, ls))
        return false;
    *lightPdf = selectPmf * ls->pdf;
    *infinite = light->isInfinite();
    return true;
}

template <bool kMedia>
Rgb PathWalk<kMedia>::visibility(const Ray& shadow, const Medium* medium, bool infinite,
                                 float* survival) const {
    if constexpr (kMedia) {
        return shadowTransmittance(scene_, shadow, medium, infinite, survival, rays_);
    } else {
        *survival = 1;
        ++rays_.shadow;
        return Rgb(scene_.occluded(shadow) ? 0.0f : 1.0f);
    }
}

}  // namespace

nlohmann::json PathTracer::parameters() const {
    return {{"type", name()}, {"max_depth", settings_.maxDepth}, {"rr_depth", settings_.rrDepth}};
}

Rgb PathTracer::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const {
    const Ray cameraRay = generateCameraRay(scene.camera(), x, y, sample);
    ++rays.camera;
    if (scene.features().media)
        return PathWalk<true>(scene, sample, rays, settings_, nee_, cameraRay).run();
    return PathWalk<false>(scene, sample, rays, settings_, nee_, cameraRay).run();
}

}  // namespace rr
