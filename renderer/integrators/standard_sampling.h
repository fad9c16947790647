// How a path makes its decisions: the Guide contract of the path walk (path_walk.h), and
// StandardSampling, plain importance sampling, which `path` and `path_mis` use and which a
// technique extends by hiding the members whose decisions it steers (TAIS's MapGuide). The walk
// is a template on its guide, so StandardSampling compiles away entirely.
//
// Which light next-event estimation samples is StandardSampling's light-selection policy: the
// scene's selector (/render/light_selection) in `path_mis`, any other in
// StandardSamplingWith<Policy>. The policy serves sampleLight() and both lightPdf(), so the
// selection drawn and the density every MIS weight divides by agree. It applies wherever the
// path's estimator draws a light through the guide (ShadingPoint::sampleLight: `light`, `mis`,
// RIS's light, light_proxy and mixture sources, PMC-HI with one component for all lights) or
// asks the density of light sampling (emission a BSDF or phase sample finds, the
// ShadingPoint's infiniteLightPdf and incidentEmission with selection). Estimators that draw
// from one light they name (ShadingPoint::sampleLightOf: PMC-HI's per-light components;
// two-stage sampling's single environment map) select no light, and no policy changes them.
//
// `vertex` is the index of the scattering vertex that makes a decision (0: the first one the
// camera ray reaches); `radiance` is what the path has gathered before the decision, so a guide
// can credit a decision with what follows it. A guide that changes a decision's density must
// report the changed density from the matching *Pdf member, which the walk uses in every
// sample weight and MIS weight, so that the estimate stays unbiased.
#pragma once

#include <array>
#include <concepts>
#include <utility>

#include "integrators/camera_ray.h"
#include "scene/light_selector.h"
#include "scene/light_stand_in.h"
#include "scene/lights/area_light.h"
#include "scene/scene.h"

namespace rr {

// A light-selection policy: picks a light for next-event estimation from a reference point with
// coordinate u, giving its probability, and tells the probability of any light; nullptr when
// it picks none. select() and pmf() must agree, as LightSelector's do.
template <class P>
concept LightSelectionPolicy = requires(const P& p, float u, const Vec3& reference, float* pmf,
                                        const Light& light) {
    { p.select(u, reference, pmf) } -> std::same_as<const Light*>;
    { p.pmf(light, reference) } -> std::same_as<float>;
};

// The scene's light selector (/render/light_selection): `path_mis`'s policy.
class SceneLightSelection {
  public:
    explicit SceneLightSelection(const Scene& scene) : selector_(scene.lightSelector()) {}
    const Light* select(float u, const Vec3& reference, float* pmf) const {
        return selector_.select(u, reference, pmf);
    }
    float pmf(const Light& light, const Vec3& reference) const {
        return selector_.pmf(light, reference);
    }

  private:
    const LightSelector& selector_;
};

template <LightSelectionPolicy Selection>
class StandardSamplingWith {
  public:
    // The policy made from the scene (as each pixel sample's guide is made: keep it cheap),
    // or given.
    StandardSamplingWith(const Scene& scene, const PixelSample& sample) requires
        std::constructible_from<Selection, const Scene&>
        : StandardSamplingWith(scene, sample, Selection(scene)) {}
    StandardSamplingWith(const Scene& scene, const PixelSample& sample, Selection selection)
        : scene_(scene), sample_(sample), selection_(std::move(selection)) {}
    // The guide keeps a reference to the sample: a temporary would dangle.
    StandardSamplingWith(const Scene& scene, const PixelSample&& sample) = delete;
    StandardSamplingWith(const Scene& scene, const PixelSample&& sample, Selection) = delete;

    // The camera ray through pixel (x, y) and its sampling weight (1 unless the guide warps
    // the camera's decisions).
    Ray cameraRay(int x, int y, float* weight) {
        *weight = 1;
        return generateCameraRay(scene_.camera(), x, y, sample_);
    }
    // The coordinate of the free flight of the segment that leads to `vertex` (the camera
    // ray's for vertex 0), and the density of any warp applied to it.
    float flightCoordinate(uint32_t vertex, const Rgb& /*radiance*/, float* warpPdf) {
        *warpPdf = 1;
        return sample_.get1D(Decision::MediumDistance, vertex);
    }
    // Draw `repeat` of `count` of next-event estimation's light and the point on it (from the
    // light's stand-in in `standIns` when it has one: ShadingPoint::sampleLight), with the
    // density of the pair.
    bool sampleLight(uint32_t vertex, uint32_t repeat, uint32_t count,
                     const LightStandIns* standIns, const LightReference& reference, float time,
                     LightSample* ls, float* pdf, const Light** chosen) {
        float selectPmf;
        const Light* light = selection_.select(
            sample_.get1D(DecisionSite{Decision::LightSelect, vertex, repeat, count}),
            reference.point, &selectPmf);
        if (!light) return false;
        const Vec2 u = sample_.get2D(DecisionSite{Decision::LightPoint, vertex, repeat, count});
        if (!sampleLightOrStandIn(*light, standIns, reference, u, time, ls)) return false;
        *pdf = selectPmf * ls->pdf;
        *chosen = light;
        return true;
    }
    // Draws `repeats` (each of `count`) of sampleLight() at once (ShadingPoint::sampleLights):
    // every draw's light and coordinates first, then each light's draws together
    // (Light::sampleMany), so that a light's table reads overlap. Each draw is what
    // sampleLight() would give it.
    void sampleLights(uint32_t vertex, std::span<const uint32_t> repeats, uint32_t count,
                      const LightStandIns* standIns, const LightReference& reference, float time,
                      LightDraw* out) {
        for (size_t start = 0; start < repeats.size(); start += kLightChunk)
            sampleLightChunk(vertex,
                             repeats.subspan(start, std::min(kLightChunk, repeats.size() - start)),
                             count, standIns, reference, time, out + start);
    }
    // A light sample's contribution (already weighted and scaled by the path) at `vertex`.
    void lightContribution(uint32_t /*vertex*/, const Rgb& /*contribution*/) {}
    // Density with which sampleLight() at `vertex` picks `light` and its point `hit`.
    float lightPdf(uint32_t /*vertex*/, const AreaLight& light, const LightReference& reference,
                   const SurfaceHit& hit) const {
        return selection_.pmf(light, reference.point) * light.pdf(reference.point, hit);
    }
    // The same for an infinite light seen in direction `w`.
    float lightPdf(uint32_t /*vertex*/, const Light& light, const LightReference& reference,
                   const Vec3& w) const {
        return selection_.pmf(light, reference.point) * light.directionPdf(reference, w);
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
    // The scattering direction at a medium vertex (the BsdfDirection decision there) and its
    // density (0: no sample).
    float samplePhase(uint32_t vertex, const PhaseFunction& phase, const Vec3& wo, Vec3* wi) {
        return phase.sample(wo, sample_.get2D(Decision::BsdfDirection, vertex), wi);
    }
    float phasePdf(uint32_t /*vertex*/, const PhaseFunction& phase, const Vec3& wo,
                   const Vec3& wi) const {
        return phase.pdf(wo, wi);
    }

    const PixelSample& sample() const { return sample_; }
    const Scene& scene() const { return scene_; }

  private:
    static constexpr size_t kLightChunk = 16;
    // sampleLights() for at most kLightChunk draws.
    void sampleLightChunk(uint32_t vertex, std::span<const uint32_t> repeats, uint32_t count,
                          const LightStandIns* standIns, const LightReference& reference,
                          float time, LightDraw* out) {
        const uint32_t n = uint32_t(repeats.size());
        std::array<float, kLightChunk> selectPmf;
        std::array<Vec2, kLightChunk> u;
        std::array<bool, kLightChunk> done{};
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t repeat = repeats[i];
            out[i].light = selection_.select(
                sample_.get1D(DecisionSite{Decision::LightSelect, vertex, repeat, count}),
                reference.point, &selectPmf[i]);
            u[i] = sample_.get2D(DecisionSite{Decision::LightPoint, vertex, repeat, count});
            out[i].drawn = false;
            done[i] = !out[i].light;
        }
        // Each light's draws in one call, in the order of their first draw.
        std::array<Vec2, kLightChunk> us;
        std::array<LightSample, kLightChunk> samples;
        std::array<bool, kLightChunk> drawn;
        std::array<uint32_t, kLightChunk> which;
        for (uint32_t i = 0; i < n; ++i) {
            if (done[i]) continue;
            const Light& light = *out[i].light;
            uint32_t k = 0;
            for (uint32_t j = i; j < n; ++j)
                if (!done[j] && out[j].light == &light) {
                    which[k] = j;
                    us[k++] = u[j];
                    done[j] = true;
                }
            const LightStandIn* standIn = standIns ? standIns->of(light) : nullptr;
            if (standIn) {
                for (uint32_t m = 0; m < k; ++m)
                    drawn[m] = standIn->sampleStandIn(reference, us[m], time, &samples[m]);
            } else {
                light.sampleMany(reference, std::span(us.data(), k), time, samples.data(),
                                 drawn.data());
            }
            for (uint32_t m = 0; m < k; ++m) {
                LightDraw& d = out[which[m]];
                d.drawn = drawn[m];
                d.sample = samples[m];
                d.pdf = selectPmf[which[m]] * samples[m].pdf;
            }
        }
    }

    const Scene& scene_;
    const PixelSample& sample_;
    Selection selection_;
};

using StandardSampling = StandardSamplingWith<SceneLightSelection>;

// The contract StandardSampling defines: what the path walk asks of a guide.
template <class G>
concept PathGuide = requires(G& g, const G& cg, int pixel, uint32_t index, float* out,
                             const Rgb& radiance, const Vec3& v, LightSample* ls,
                             const Light** chosen, const AreaLight& areaLight, const Light& light,
                             const SurfaceHit& hit, const Material& material,
                             const ShadingContext& ctx, const Frame& frame, BsdfSample* bs,
                             const PhaseFunction& phase, Vec3* wi) {
    { g.cameraRay(pixel, pixel, out) } -> std::same_as<Ray>;
    { g.flightCoordinate(index, radiance, out) } -> std::same_as<float>;
    { g.sampleLight(index, index, index, nullptr, v, 0.0f, ls, out, chosen) } -> std::same_as<bool>;
    g.lightContribution(index, radiance);
    { cg.lightPdf(index, areaLight, v, hit) } -> std::same_as<float>;
    { cg.lightPdf(index, light, v, v) } -> std::same_as<float>;
    { g.sampleBsdf(index, material, ctx, frame, v, radiance, bs) } -> std::same_as<bool>;
    { cg.bsdfPdf(index, material, ctx, frame, v, v) } -> std::same_as<float>;
    { g.samplePhase(index, phase, v, wi) } -> std::same_as<float>;
    { cg.phasePdf(index, phase, v, v) } -> std::same_as<float>;
    { cg.sample() } -> std::same_as<const PixelSample&>;
    { cg.scene() } -> std::same_as<const Scene&>;
};

}  // namespace rr
