#include "integrators/path_tracer.h"

#include <algorithm>

#include "scene/lights/area_light.h"

namespace rr {

nlohmann::json PathTracer::parameters() const {
    return {{"type", name()}, {"max_depth", settings_.maxDepth}, {"rr_depth", settings_.rrDepth}};
}

Rgb PathTracer::sampleLight(const Scene& scene, const SurfaceHit& hit, const Material& material,
                            const ShadingContext& ctx, const Frame& frame, const Vec3& wo,
                            const PixelSample& sample, uint32_t vertex, RayCounters& rays) const {
    float selectPmf;
    const Light* light = scene.lightSelector().select(sample.get1D(Decision::LightSelect, vertex),
                                                      hit.position, &selectPmf);
    if (!light) return Rgb(0.0f);
    LightSample ls;
    if (!light->sample(hit.position, sample.get2D(Decision::LightPoint, vertex), hit.time, &ls))
        return Rgb(0.0f);
    const Vec3 wi = frame.toLocal(ls.direction);
    const Rgb f = material.eval(ctx, wo, wi);
    if (f.isBlack()) return Rgb(0.0f);
    ++rays.shadow;
    if (scene.occluded(hit.spawnTo(ls.position, ls.normal, ls.errorScale))) return Rgb(0.0f);

    const float lightPdf = selectPmf * ls.pdf;
    const float weight =
        ls.isDelta ? 1.0f : powerHeuristic(1, lightPdf, 1, material.pdf(ctx, wo, wi));
    return f * ls.radiance * (weight / lightPdf);
}

Rgb PathTracer::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const {
    Ray ray = generateCameraRay(scene.camera(), x, y, sample);
    const int maxDepth = settings_.maxDepth < 0 ? kDepthCap : settings_.maxDepth;

    Rgb radiance(0.0f), throughput(1.0f);
    // Product of η² over the refractions so far: radiance is scaled by 1/η² entering a denser
    // medium and back on leaving, which must not make Russian roulette kill paths inside glass
    // whose final weight is 1 (pbrt-v4's etaScale).
    float etaScale = 1;
    bool countEmission = true;  // camera ray, or a specular bounce, or BSDF-only tracing
    float bsdfPdf = 0;
    Vec3 previous;
    for (int depth = 0;; ++depth) {
        ++(depth == 0 ? rays.camera : rays.extension);
        SurfaceHit hit;
        if (!scene.intersect(ray, &hit)) {
            radiance += throughput *
                        escapedRadiance(scene, ray.direction, previous, countEmission, bsdfPdf);
            break;
        }

        if (const AreaLight* light = hit.shape->areaLight()) {
            const Rgb le = light->emitted(hit.geometricNormal, -ray.direction);
            if (!le.isBlack()) {
                const float lightPdf = countEmission ? 0.0f
                                                     : scene.lightSelector().pmf(*light, previous) *
                                                           light->pdf(previous, hit);
                radiance += throughput * le * emissionMisWeight(countEmission, bsdfPdf, lightPdf);
            }
        }
        const Material* material = hit.shape->material();
        if (depth >= maxDepth || !material) break;

        const uint32_t vertex = static_cast<uint32_t>(depth);
        const Frame frame = hit.shadingFrame();
        const Vec3 wo = frame.toLocal(-ray.direction);
        const ShadingContext ctx{hit.uv, hit.position};
        if (nee_ && material->hasNonSpecular())
            radiance += throughput *
                        sampleLight(scene, hit, *material, ctx, frame, wo, sample, vertex, rays);

        BsdfSample bs;
        if (!material->sample(ctx, wo, sample.get1D(Decision::BsdfLobe, vertex),
                              sample.get2D(Decision::BsdfDirection, vertex), &bs))
            break;
        throughput *= bs.weight;
        etaScale *= bs.eta * bs.eta;
        if (throughput.isBlack()) break;
        countEmission = !nee_ || bs.isSpecular();
        bsdfPdf = bs.pdf;
        previous = hit.position;
        ray = hit.spawn(frame.toWorld(bs.wi));

        if (depth + 1 >= settings_.rrDepth) {
            const float survive = std::min(1.0f, throughput.maxComponent() * etaScale);
            if (sample.get1D(Decision::RussianRoulette, vertex) >= survive) break;
            throughput *= 1.0f / survive;
        }
    }
    return radiance;
}

}  // namespace rr
