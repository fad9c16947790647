#include "integrators/direct_lighting.h"

#include "integrators/light_sample_estimator.h"
#include "integrators/scattering_vertex.h"

namespace rr {

nlohmann::json DirectLighting::parameters() const {
    return {{"type", name()},
            {"strategy", estimator_->name()},
            {"estimator", estimator_->parameters()},
            {"bsdf_samples", bsdfSamples_}};
}

Rgb DirectLighting::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                             RayCounters& rays) const {
    StandardSampling standard(scene, sample);
    return shadeFirstHit(
        scene, standard, x, y, rays,
        [&](const SurfaceHit& hit, const Material& material, const ShadingContext& ctx,
            const Frame& frame, const Vec3& wo, Rgb* radiance) {
            if (estimator_->lightSamples() > 0) {
                const Rgb unscaled(1.0f);
                const VertexOutput<StandardSampling> out{standard,  0,    unscaled,
                                                         *radiance, rays, records_.slot(x, y)};
                SurfaceVertex<false, StandardSampling> point(
                    out, hit, material, ctx, frame, wo, nullptr,
                    static_cast<float>(tracedBsdfSamples()));
                runEstimator(*estimator_, point);
            }
            addBsdfSamples(standard, hit, material, ctx, frame, wo, rays, radiance);
        });
}

void DirectLighting::addBsdfSamples(const StandardSampling& standard, const SurfaceHit& hit,
                                    const Material& material, const ShadingContext& ctx,
                                    const Frame& frame, const Vec3& wo, RayCounters& rays,
                                    Rgb* radiance) const {
    const Scene& scene = standard.scene();
    const uint32_t n = tracedBsdfSamples();
    const float nBsdf = static_cast<float>(n);
    const LightReference reference(hit.position, frame.n);  // as SurfaceVertex samples lights
    for (uint32_t r = 0; r < n; ++r) {
        BsdfSample bs;
        if (!material.sample(ctx, wo, standard.sample().get1D({Decision::BsdfLobe, 0, r, n}),
                             standard.sample().get2D({Decision::BsdfDirection, 0, r, n}), &bs))
            continue;
        ++rays.extension;
        SurfaceHit lightHit;
        const Vec3 wi = frame.toWorld(bs.wi);
        // The weight of the emission found, divided by the number of samples.
        auto weight = [&](const auto& lightPdf) {
            return foundEmissionWeight(*estimator_, bs.isSpecular(), nBsdf, bs.pdf, lightPdf) /
                   nBsdf;
        };
        if (!scene.intersect(hit.spawn(wi), &lightHit)) {
            *radiance +=
                bs.weight * escapedRadiance(scene, wi, [&](const Light& light) {
                    return weight([&] { return standard.lightPdf(0, light, reference, wi); });
                });
            continue;
        }
        const AreaLight* light = lightHit.shape->areaLight();
        if (!light) continue;
        const Rgb le = light->emitted(lightHit.geometricNormal, -wi);
        if (le.isBlack()) continue;
        *radiance += bs.weight * le *
                     weight([&] { return standard.lightPdf(0, *light, reference, lightHit); });
    }
}

}  // namespace rr
