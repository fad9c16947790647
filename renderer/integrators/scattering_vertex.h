// The two kinds of path vertex as shading points for direct-lighting estimators
// (shading_point.h): a surface vertex and, in scenes with media, a medium vertex. Both sample
// lights through the path's guide, trace shadow rays through media when the walk has them
// (kMedia), and add what the estimator finds, scaled by the path's throughput, to the
// radiance the path gathers.
#pragma once

#include <stdexcept>

#include "integrators/medium_tracking.h"
#include "integrators/pixel_records.h"
#include "integrators/shading_point.h"
#include "integrators/standard_sampling.h"

namespace rr {

// What reaches the end of `shadow`, which starts in `medium`: the transmittance, or without
// media 0 or 1; *survival: the free-flight survival probability over it.
template <bool kMedia>
Rgb traceShadowRay(const Scene& scene, const Ray& shadow, const Medium* medium, bool infinite,
                   float* survival, RayCounters& rays) {
    if constexpr (kMedia) {
        return shadowTransmittance(scene, shadow, medium, infinite, survival, rays);
    } else {
        *survival = 1;
        ++rays.shadow;
        return Rgb(scene.occluded(shadow) ? 0.0f : 1.0f);
    }
}

// The density with which `guide` picks direction `w` at `vertex` from `reference`, over the
// scene's infinite lights, and their radiance along it (ShadingPoint::infiniteLightPdf).
template <PathGuide Guide>
float infiniteLightPdf(const Guide& guide, uint32_t vertex, const LightReference& reference,
                       const Vec3& w, Rgb* radiance) {
    float pdf = 0;
    *radiance = Rgb(0.0f);
    for (const Light* light : guide.scene().infiniteLights()) {
        pdf += guide.lightPdf(vertex, *light, reference, w);
        *radiance += light->escapedRadiance(w);
    }
    return pdf;
}

// Where a vertex's estimate goes: the path's radiance, scaled by its throughput, and the
// guide's credit.
template <class Guide>
struct VertexOutput {
    Guide& guide;
    uint32_t vertex;
    const Rgb& throughput;
    Rgb& radiance;
    RayCounters& rays;
    PixelRecordSlot pixel;  // the pixel's records (pixel_records.h), at a first hit

    void add(const Rgb& contribution) const {
        const Rgb scaled = throughput * contribution;
        guide.lightContribution(vertex, scaled);
        radiance += scaled;
    }
    float decide1D(Decision d, uint32_t repeat, uint32_t count) const {
        return guide.sample().get1D(DecisionSite{d, vertex, repeat, count});
    }
    Vec2 decide2D(Decision d, uint32_t repeat, uint32_t count) const {
        return guide.sample().get2D(DecisionSite{d, vertex, repeat, count});
    }
};

// Whether a guide draws light samples in batches (StandardSamplingWith::sampleLights); a guide
// that steers light samples one at a time (TAIS's) does not.
template <class Guide>
concept DrawsLightBatches = requires(Guide& g, uint32_t index, std::span<const uint32_t> repeats,
                                     LightDraw* out) {
    g.sampleLights(index, repeats, index, nullptr, LightReference(Vec3(0.0f)), 0.0f, out);
};

template <bool kMedia, PathGuide Guide>
class SurfaceVertex final : public ShadingPoint {
  public:
    // `wo`: local frame; `medium`: the one the arriving ray travelled in; `scatterSamples`:
    // the BSDF samples the integrator combines with the estimate.
    SurfaceVertex(const VertexOutput<Guide>& out, const SurfaceHit& hit, const Material& material,
                  const ShadingContext& ctx, const Frame& frame, const Vec3& wo,
                  const Medium* medium, float scatterSamples)
        : out_(out),
          hit_(hit),
          material_(material),
          ctx_(ctx),
          frame_(frame),
          wo_(wo),
          medium_(medium),
          scatterSamples_(scatterSamples) {}

    bool sampleLight(uint32_t repeat, uint32_t count, const LightStandIns* standIns,
                     LightSample* ls, float* pdf, const Light** light) override {
        return out_.guide.sampleLight(out_.vertex, repeat, count, standIns, lightReference(),
                                      hit_.time, ls, pdf, light);
    }
    static constexpr bool kDrawsLightBatches = DrawsLightBatches<Guide>;
    void sampleLights(std::span<const uint32_t> repeats, uint32_t count,
                      const LightStandIns* standIns, LightDraw* out) override {
        if constexpr (kDrawsLightBatches)
            out_.guide.sampleLights(out_.vertex, repeats, count, standIns, lightReference(),
                                    hit_.time, out);
        else
            ShadingPoint::sampleLights(repeats, count, standIns, out);
    }
    Rgb scattering(const Vec3& wi) const override {
        return material_.eval(ctx_, wo_, frame_.toLocal(wi));
    }
    float scatteringPdf(const Vec3& wi) const override {
        return out_.guide.bsdfPdf(out_.vertex, material_, ctx_, frame_, wo_, frame_.toLocal(wi));
    }
    float scatteringSamples() const override { return scatterSamples_; }
    Rgb visibility(const LightSample& ls, bool infinite, float* survival) override {
        const Medium* medium =
            kMedia ? mediumOnSide(out_.guide.scene(), hit_, ls.direction, medium_) : nullptr;
        return traceShadowRay<kMedia>(out_.guide.scene(),
                                      hit_.spawnTo(ls.position, ls.normal, ls.errorScale), medium,
                                      infinite, survival, out_.rays);
    }
    Rgb contribution(const Rgb& f, const Rgb& le, const Rgb& tr, float misWeight,
                     float density) const override {
        return f * le * tr * (misWeight / density);
    }
    float decide1D(Decision d, uint32_t repeat, uint32_t count) const override {
        return out_.decide1D(d, repeat, count);
    }
    Vec2 decide2D(Decision d, uint32_t repeat, uint32_t count) const override {
        return out_.decide2D(d, repeat, count);
    }
    const Frame* frame() const override { return &frame_; }
    Vec3 position() const override { return hit_.position; }
    bool scatteringShape(const LobePeakSources* peaks, ScatteringShape* out) const override {
        out->normal = wo_.z < 0 ? -frame_.n : frame_.n;
        out->transmits = material_.hasTransmission();
        out->peaks.count = 0;
        if (!peaks) return true;
        LobePeaks local;
        peaks->of(material_)->peaks(ctx_, wo_, &local);
        for (int i = 0; i < local.count; ++i)
            out->peaks.add(frame_.toWorld(local.directions[i]));
        return true;
    }
    bool sampleScattering(float uLobe, const Vec2& u, Vec3* wi, float* pdf) const override {
        BsdfSample bs;
        if (!material_.sample(ctx_, wo_, uLobe, u, &bs) || bs.isSpecular()) return false;
        *wi = frame_.toWorld(bs.wi);
        *pdf = bs.pdf;
        return true;
    }
    float sampleScatteringPdf(const Vec3& wi) const override {
        return material_.pdf(ctx_, wo_, frame_.toLocal(wi));
    }
    using ShadingPoint::incidentEmission;
    Rgb incidentEmission(const Vec3& wi, EmissionSource* source) override {
        if constexpr (kMedia) {
            // Refused at load (DirectLightingEstimator::worksInMedia): transmittance to the
            // emitter would need the medium walk.
            throw std::logic_error("incidentEmission in a scene with media");
        } else {
            ++out_.rays.extension;
            const Scene& scene = out_.guide.scene();
            SurfaceHit lightHit;
            if (source) *source = EmissionSource{.withSelection = source->withSelection};
            if (!scene.intersect(hit_.spawn(wi), &lightHit)) {
                if (source) source->escaped = true;
                if (!source || !source->withSelection)
                    return escapedRadiance(scene, wi, [](const Light&) { return 1.0f; });
                // The infinite lights' radiance and density in one pass over them.
                Rgb radiance;
                source->selectedLightPdf = infiniteLightPdf(wi, &radiance);
                return radiance;
            }
            const AreaLight* light = lightHit.shape->areaLight();
            if (!light) return Rgb(0.0f);
            if (source) {
                source->areaLight = light;
                source->areaLightPdf = light->pdf(hit_.position, lightHit);
                if (source->withSelection)
                    source->selectedLightPdf =
                        out_.guide.lightPdf(out_.vertex, *light, lightReference(), lightHit);
            }
            return light->emitted(lightHit.geometricNormal, -wi);
        }
    }
    bool sampleLightOf(const Light& light, const Vec2& u, LightSample* ls) const override {
        return light.sample(lightReference(), u, hit_.time, ls);
    }
    float infiniteLightPdf(const Vec3& wi, Rgb* radiance) const override {
        return rr::infiniteLightPdf(out_.guide, out_.vertex, lightReference(), wi, radiance);
    }
    void add(const Rgb& contribution) override { out_.add(contribution); }
    void record(std::span<const float> values) override { out_.pixel.add(values); }
    const float* recordedStart() const override { return out_.pixel.start; }

  private:
    VertexOutput<Guide> out_;
    const SurfaceHit& hit_;
    const Material& material_;
    const ShadingContext& ctx_;
    const Frame& frame_;
    const Vec3& wo_;
    const Medium* medium_;
    float scatterSamples_;
};

template <PathGuide Guide>
class MediumVertex final : public ShadingPoint {
  public:
    // `wo`: world space, back along the arriving ray; one phase sample continues the path.
    MediumVertex(const VertexOutput<Guide>& out, const Vec3& position, float time, const Vec3& wo,
                 const Medium& medium)
        : out_(out), position_(position), time_(time), wo_(wo), medium_(medium) {}

    bool sampleLight(uint32_t repeat, uint32_t count, const LightStandIns* standIns,
                     LightSample* ls, float* pdf, const Light** light) override {
        return out_.guide.sampleLight(out_.vertex, repeat, count, standIns, position_, time_, ls,
                                      pdf, light);
    }
    static constexpr bool kDrawsLightBatches = DrawsLightBatches<Guide>;
    void sampleLights(std::span<const uint32_t> repeats, uint32_t count,
                      const LightStandIns* standIns, LightDraw* out) override {
        if constexpr (kDrawsLightBatches)
            out_.guide.sampleLights(out_.vertex, repeats, count, standIns, position_, time_, out);
        else
            ShadingPoint::sampleLights(repeats, count, standIns, out);
    }
    Rgb scattering(const Vec3& wi) const override {
        const float p = medium_.phase().eval(wo_, wi);
        return Rgb(p > 0 ? p : 0.0f);
    }
    float scatteringPdf(const Vec3& wi) const override {
        return out_.guide.phasePdf(out_.vertex, medium_.phase(), wo_, wi);
    }
    float scatteringSamples() const override { return 1; }
    Rgb visibility(const LightSample& ls, bool infinite, float* survival) override {
        // A medium point lies on no surface: only the light's end of the shadow ray is lifted.
        const Vec3 target =
            offsetRayOrigin(ls.position, ls.normal, position_ - ls.position, ls.errorScale);
        const float distance = length(target - position_);
        const Ray shadow{position_, (target - position_) / distance, distance, time_};
        return shadowTransmittance(out_.guide.scene(), shadow, &medium_, infinite, survival,
                                   out_.rays);
    }
    Rgb contribution(const Rgb& f, const Rgb& le, const Rgb& tr, float misWeight,
                     float density) const override {
        return le * tr * (f.r * misWeight / density);
    }
    float decide1D(Decision d, uint32_t repeat, uint32_t count) const override {
        return out_.decide1D(d, repeat, count);
    }
    Vec2 decide2D(Decision d, uint32_t repeat, uint32_t count) const override {
        return out_.decide2D(d, repeat, count);
    }
    const Frame* frame() const override { return nullptr; }
    Vec3 position() const override { return position_; }
    bool scatteringShape(const LobePeakSources*, ScatteringShape*) const override { return false; }
    bool sampleScattering(float, const Vec2& u, Vec3* wi, float* pdf) const override {
        *pdf = medium_.phase().sample(wo_, u, wi);
        return *pdf > 0;
    }
    float sampleScatteringPdf(const Vec3& wi) const override {
        return medium_.phase().pdf(wo_, wi);
    }
    using ShadingPoint::incidentEmission;
    Rgb incidentEmission(const Vec3&, EmissionSource*) override {
        // Refused at load (DirectLightingEstimator::worksInMedia).
        throw std::logic_error("incidentEmission at a point in a medium");
    }
    bool sampleLightOf(const Light& light, const Vec2& u, LightSample* ls) const override {
        return light.sample(position_, u, time_, ls);
    }
    float infiniteLightPdf(const Vec3& wi, Rgb* radiance) const override {
        return rr::infiniteLightPdf(out_.guide, out_.vertex, position_, wi, radiance);
    }
    void add(const Rgb& contribution) override { out_.add(contribution); }

  private:
    VertexOutput<Guide> out_;
    Vec3 position_;
    float time_;
    Vec3 wo_;
    const Medium& medium_;
};

}  // namespace rr
