// Direct illumination only: emission seen by the camera plus light that reaches the first hit
// from an emitter in one bounce. A direct-lighting estimator (`light`, `bsdf`, `mis`, or a
// technique's) makes the light samples; the integrator adds `bsdfSamples` BSDF samples of its
// own, whose emission counts as the estimator says (in full, MIS-weighted with sample counts,
// Veach 1997 §9.2, or not at all, in which case they are not traced). Draws of one decision
// per pixel sample are stratified together by structured samplers.
#pragma once

#include <algorithm>
#include <memory>

#include "integrators/direct_lighting_estimator.h"
#include "integrators/integrator.h"
#include "integrators/pixel_records.h"
#include "integrators/scattering_vertex.h"
#include "integrators/standard_sampling.h"

namespace rr {

// The radiance a camera ray of pixel (x, y) finds up to its first hit: the infinite lights when
// it escapes, the emission of what it hits, and at a surface with a non-specular lobe whatever
// `shade(hit, material, ctx, frame, wo, &radiance)` adds (scenes without media).
template <class Shade>
Rgb shadeFirstHit(const Scene& scene, StandardSampling& standard, int x, int y, RayCounters& rays,
                  const Shade& shade) {
    float cameraWeight;
    const Ray cameraRay = standard.cameraRay(x, y, &cameraWeight);
    ++rays.camera;
    SurfaceHit hit;
    if (!scene.intersect(cameraRay, &hit))
        return escapedRadiance(scene, cameraRay.direction, [](const Light&) { return 1.0f; });

    Rgb radiance(0.0f);
    if (const AreaLight* light = hit.shape->areaLight())
        radiance += light->emitted(hit.geometricNormal, -cameraRay.direction);
    const Material* material = hit.shape->material();
    if (!material || !material->hasNonSpecular()) return radiance;

    const Frame frame = hit.shadingFrame();
    const Vec3 wo = frame.toLocal(-cameraRay.direction);
    const ShadingContext ctx{hit.uv, hit.position};
    shade(hit, *material, ctx, frame, wo, &radiance);
    return radiance;
}

// shadeFirstHit for integrators that shade the first hit with an estimator of their own:
// calls `use(point)` with the surface point there (scenes without media), whose estimates add
// to the radiance the camera ray found.
template <class Use>
Rgb estimateAtFirstHit(const Scene& scene, StandardSampling& standard, int x, int y,
                       RayCounters& rays, const Use& use) {
    return shadeFirstHit(
        scene, standard, x, y, rays,
        [&](const SurfaceHit& hit, const Material& material, const ShadingContext& ctx,
            const Frame& frame, const Vec3& wo, Rgb* radiance) {
            const Rgb unscaled(1.0f);
            const VertexOutput<StandardSampling> out{standard, 0, unscaled, *radiance, rays, {}};
            SurfaceVertex<false, StandardSampling> point(out, hit, material, ctx, frame, wo,
                                                         nullptr, 0);
            use(point);
        });
}

class DirectLighting final : public SampleIntegrator {
  public:
    DirectLighting(std::unique_ptr<DirectLightingEstimator> estimator, uint32_t bsdfSamples)
        : estimator_(std::move(estimator)), bsdfSamples_(bsdfSamples) {}

    std::string name() const override { return "direct"; }
    LightTransport transport() const override { return LightTransport::Direct; }
    bool samplesLights() const override { return estimator_->samplesLights(); }
    nlohmann::json parameters() const override;
    Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                 RayCounters& rays) const override;
    uint32_t decisionRepeats() const override {
        return std::max({1u, estimator_->decisionRepeats(), bsdfSamples_});
    }
    void prepare(const Scene& scene) override {
        estimator_->prepare(scene, "/integrator/estimator");
    }
    void beginImage(int width, int height, bool iterated) override {
        records_.begin(width, height, iterated, estimator_->pixelRecords(),
                       "/integrator/estimator");
    }
    void commitPixelRecords() override { records_.commit(); }
    std::vector<AuxiliaryChannel> auxiliaryChannels() const override { return records_.channels(); }

  private:
    // The BSDF samples traced per pixel sample.
    uint32_t tracedBsdfSamples() const {
        return estimator_->foundEmission() == FoundEmission::Excluded ? 0 : bsdfSamples_;
    }
    // Adds each BSDF sample's emission at `hit` to *radiance, weighted against the estimator's
    // light samples.
    void addBsdfSamples(const StandardSampling& standard, const SurfaceHit& hit,
                        const Material& material, const ShadingContext& ctx, const Frame& frame,
                        const Vec3& wo, RayCounters& rays, Rgb* radiance) const;

    std::unique_ptr<DirectLightingEstimator> estimator_;
    uint32_t bsdfSamples_;
    // Written by estimate() at pixels its caller renders alone (render_schedule.h).
    mutable PixelRecords records_;
};

}  // namespace rr
