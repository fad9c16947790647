// The vertex where a direct-lighting estimator works: a surface point (its BSDF) or a point in a
// medium (its phase function), as the integrator that owns it sees it. The integrator decides
// how light is sampled (a technique's guide may steer it), how the shadow ray runs (through
// media or not) and how many scattering samples of its own are combined with the estimate; the
// estimator only asks. Directions are world-space unit vectors pointing towards the light.
#pragma once

#include <cstdint>
#include <span>

#include "math/frame.h"
#include "math/rgb.h"
#include "sampling/sampler.h"
#include "scene/light.h"
#include "scene/light_stand_in.h"
#include "scene/lobe_peaks.h"
#include "scene/material.h"

namespace rr {

// Where a surface point scatters, for estimators that partition the sphere of directions
// (two-stage sampling): the shading normal on the viewer's side, whether scattering also
// reaches the other side (transmission), and, when asked for, the directions where its lobes
// peak (world).
struct ScatteringShape {
    Vec3 normal;
    bool transmits = false;
    LobePeaks peaks;
};

// Where the emission along a direction comes from (ShadingPoint::incidentEmission): the area
// light the ray hit and the solid-angle density with which that light's own sampler picks the
// point (Light::pdf), and, when `withSelection` is asked for, with which sampleLight() picks it
// (the light's selection included); or that the ray escaped to the infinite lights (then, with
// `withSelection`, selectedLightPdf is infiniteLightPdf() of the direction); or neither.
struct EmissionSource {
    bool withSelection = false;  // in: also fill selectedLightPdf
    const Light* areaLight = nullptr;
    float areaLightPdf = 0;
    float selectedLightPdf = 0;
    bool escaped = false;
};

class ShadingPoint {
  public:
    virtual ~ShadingPoint() = default;

    // Whether sampleLights() draws batches in one go (a vertex type whose guide does), or one
    // sample at a time; for callers that interleave draws with other work per sample.
    static constexpr bool kDrawsLightBatches = false;

    // Draw `repeat` of `count` of a light and a point on it (the light-selection and
    // light-point decisions of this vertex), from the light's stand-in in `standIns` when it has
    // one there, from its own sampler otherwise (standIns nullptr: always): the sample, its
    // density (selection × point, per solid angle) and the light. False when no light was
    // sampled.
    virtual bool sampleLight(uint32_t repeat, uint32_t count, const LightStandIns* standIns,
                             LightSample* sample, float* pdf, const Light** light) = 0;
    // Draws `repeats` (each of `count`) at once, out[i] as sampleLight() draws repeats[i], so
    // that the lights can overlap their memory reads (Light::sampleMany): for estimators that
    // draw many light samples at one point (resampling's candidates).
    virtual void sampleLights(std::span<const uint32_t> repeats, uint32_t count,
                              const LightStandIns* standIns, LightDraw* out) {
        for (size_t i = 0; i < repeats.size(); ++i)
            out[i].drawn = sampleLight(repeats[i], count, standIns, &out[i].sample, &out[i].pdf,
                                       &out[i].light);
    }
    // f(wo, wi)·|cos θi| at a surface; the phase function (grey) in a medium.
    virtual Rgb scattering(const Vec3& wi) const = 0;
    // The density with which this vertex's own scattering sample (BSDF or phase function,
    // as the integrator draws it) picks wi, and how many of those samples the integrator
    // combines with the estimate: the other strategy of an MIS weight.
    virtual float scatteringPdf(const Vec3& wi) const = 0;
    virtual float scatteringSamples() const = 0;
    // What reaches this point along the shadow ray to `sample` (the light's end lifted off
    // it): 0 or 1, or the transmittance of the media crossed. `*survival` receives the
    // probability that free-flight sampling crosses the same segments (1 without media), which
    // joins scatteringPdf in MIS weights.
    virtual Rgb visibility(const LightSample& sample, bool infiniteLight, float* survival) = 0;
    // A light sample's contribution f·Le·Tr·misWeight / density. In a medium f is the phase
    // function, a scalar, which joins the scalar factor.
    virtual Rgb contribution(const Rgb& f, const Rgb& le, const Rgb& tr, float misWeight,
                             float density) const = 0;
    // A coordinate of decision `d` at this vertex, draw `repeat` of `count`: for estimators
    // that make decisions of their own (resampling's candidate counts and choices).
    virtual float decide1D(Decision d, uint32_t repeat, uint32_t count) const = 0;
    virtual Vec2 decide2D(Decision d, uint32_t repeat, uint32_t count) const = 0;
    // The surface's shading frame (z along the shading normal); nullptr in a medium.
    virtual const Frame* frame() const = 0;
    // Where the point is (the shadow rays' origin, before any offset).
    virtual Vec3 position() const = 0;
    // The point and, at a surface, its shading normal: what lights sample from.
    LightReference lightReference() const {
        const Frame* f = frame();
        return f ? LightReference(position(), f->n) : LightReference(position());
    }
    // The density with which sampleLightOf(light, …) yields direction `wi` (infinite lights).
    float lightDirectionPdf(const Light& light, const Vec3& wi) const {
        return light.directionPdf(lightReference(), wi);
    }
    // The shape of the surface's scattering, its peaks from `peaks` (the scene's materials'
    // lobe peaks, which the caller checked this point's material has; nullptr: none asked for);
    // false in a medium.
    virtual bool scatteringShape(const LobePeakSources* peaks, ScatteringShape* out) const = 0;
    // A direction drawn from the vertex's own scattering distribution (BSDF or phase
    // function) with the given coordinates, and its density; false when none was drawn or the
    // draw is specular (no estimator that weighs directions can use it).
    virtual bool sampleScattering(float uLobe, const Vec2& u, Vec3* wi, float* pdf) const = 0;
    // The density with which sampleScattering() draws wi (the material's or phase function's
    // own, which a guide's scatteringPdf() need not be).
    virtual float sampleScatteringPdf(const Vec3& wi) const = 0;
    // The emitted radiance arriving from direction `wi`: the area light a ray leaving the
    // point hits, or the infinite lights when it escapes (one extension ray). Estimators that
    // sample directions rather than lights use it; surface points in scenes without media only
    // (DirectLightingEstimator::worksInMedia). *source, when given, says where it came from
    // (its area light's density costs a little: callers that need the radiance only pass none).
    virtual Rgb incidentEmission(const Vec3& wi, EmissionSource* source) = 0;
    Rgb incidentEmission(const Vec3& wi) { return incidentEmission(wi, nullptr); }
    // A point on `light` (one of the scene's), drawn by the light's own sampler with
    // coordinates `u`, without light selection: for estimators with one mixture component per
    // light (PMC-HI). Its density is the sample's pdf (solid angle).
    virtual bool sampleLightOf(const Light& light, const Vec2& u, LightSample* sample) const = 0;
    // The density with which sampleLight() draws direction `wi` towards the infinite lights,
    // summed over them (a direction is the point on every infinite light it sees), and their
    // unoccluded radiance along it: for estimators that mix light samples with directions drawn
    // otherwise (RIS's `mixture` source in scenes of infinite lights only; PMC-HI's one
    // component for all lights, for a direction that escapes).
    virtual float infiniteLightPdf(const Vec3& wi, Rgb* radiance) const = 0;
    // Adds one light sample's contribution to the radiance the integrator gathers, scaled by
    // what the path carries to this point (a technique's guide hears of it too: TAIS credits
    // its light maps with it).
    virtual void add(const Rgb& contribution) = 0;
    // An estimator's per-pixel record at this point (DirectLightingEstimator::pixelRecords):
    // kept when the point is a pixel sample's first hit and the integrator
    // keeps records, ignored otherwise.
    virtual void record(std::span<const float> /*values*/) {}
    // The pixel's records as last committed (PixelRecords::commit), at a first hit whose
    // integrator keeps them: one value per field; nullptr when there are none.
    virtual const float* recordedStart() const { return nullptr; }
};

}  // namespace rr
