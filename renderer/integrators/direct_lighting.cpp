#include "integrators/direct_lighting.h"

#include "scene/lights/area_light.h"

namespace rr {

const char* directStrategyName(DirectStrategy s) {
    switch (s) {
        case DirectStrategy::Light:
            return "light";
        case DirectStrategy::Bsdf:
            return "bsdf";
        case DirectStrategy::Mis:
            return "mis";
    }
    return "?";
}

nlohmann::json DirectLighting::parameters() const {
    return {{"type", name()},
            {"strategy", directStrategyName(settings_.strategy)},
            {"light_samples", settings_.lightSamples},
            {"bsdf_samples", settings_.bsdfSamples}};
}

float DirectLighting::weight(float nSelf, float pdfSelf, float nOther, float pdfOther) const {
    return settings_.strategy == DirectStrategy::Mis
               ? powerHeuristic(nSelf, pdfSelf, nOther, pdfOther)
               : 1.0f;
}

Rgb DirectLighting::escapedToInfiniteLights(const Scene& scene, const Vec3& w,
                                            const Vec3& reference, const BsdfSample& bs,
                                            float nBsdf, float nLight) const {
    Rgb sum(0.0f);
    for (const Light* light : scene.infiniteLights()) {
        const Rgb le = light->escapedRadiance(w);
        if (le.isBlack()) continue;
        const float misWeight =
            bs.isSpecular()
                ? 1.0f
                : weight(nBsdf, bs.pdf, nLight,
                         scene.lightSelector().pmf(*light, reference) * light->directionPdf(w));
        sum += le * (misWeight / nBsdf);
    }
    return sum;
}

Rgb DirectLighting::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                             RayCounters& rays) const {
    const Ray cameraRay = generateCameraRay(scene.camera(), x, y, sample);
    ++rays.camera;
    SurfaceHit hit;
    if (!scene.intersect(cameraRay, &hit)) return escapedRadiance(scene, cameraRay.direction);

    Rgb radiance(0.0f);
    if (const AreaLight* light = hit.shape->areaLight())
        radiance += light->emitted(hit.geometricNormal, -cameraRay.direction);
    const Material* material = hit.shape->material();
    if (!material || !material->hasNonSpecular()) return radiance;

    const Frame frame = hit.shadingFrame();
    const Vec3 wo = frame.toLocal(-cameraRay.direction);
    const ShadingContext ctx{hit.uv, hit.position};
    const float nLight = usesLights() ? static_cast<float>(settings_.lightSamples) : 0.0f;
    const float nBsdf = usesBsdf() ? static_cast<float>(settings_.bsdfSamples) : 0.0f;
    const LightSelector& selector = scene.lightSelector();

    for (int i = 0; usesLights() && i < settings_.lightSamples; ++i) {
        const auto n = static_cast<uint32_t>(settings_.lightSamples);
        const auto r = static_cast<uint32_t>(i);
        float pmf;
        const Light* light = selector.select(
            sample.get1D(DecisionSite{Decision::LightSelect, 0, r, n}), hit.position, &pmf);
        LightSample ls;
        if (!light ||
            !light->sample(hit.position, sample.get2D(DecisionSite{Decision::LightPoint, 0, r, n}),
                           hit.time, &ls))
            continue;
        const Vec3 wi = frame.toLocal(ls.direction);
        const Rgb f = material->eval(ctx, wo, wi);
        if (f.isBlack()) continue;
        ++rays.shadow;
        if (scene.occluded(hit.spawnTo(ls.position, ls.normal, ls.errorScale))) continue;
        const float lightPdf = pmf * ls.pdf;
        const float w =
            ls.isDelta ? 1.0f : weight(nLight, lightPdf, nBsdf, material->pdf(ctx, wo, wi));
        radiance += f * ls.radiance * (w / (lightPdf * nLight));
    }

    for (int i = 0; usesBsdf() && i < settings_.bsdfSamples; ++i) {
        const auto n = static_cast<uint32_t>(settings_.bsdfSamples);
        const auto r = static_cast<uint32_t>(i);
        BsdfSample bs;
        if (!material->sample(ctx, wo, sample.get1D(DecisionSite{Decision::BsdfLobe, 0, r, n}),
                              sample.get2D(DecisionSite{Decision::BsdfDirection, 0, r, n}), &bs))
            continue;
        ++rays.extension;
        SurfaceHit lightHit;
        const Vec3 wiWorld = frame.toWorld(bs.wi);
        if (!scene.intersect(hit.spawn(wiWorld), &lightHit)) {
            // Escaped: the infinite lights, weighted as area lights are below.
            radiance += bs.weight *
                        escapedToInfiniteLights(scene, wiWorld, hit.position, bs, nBsdf, nLight);
            continue;
        }
        const AreaLight* light = lightHit.shape->areaLight();
        if (!light) continue;
        const Rgb le = light->emitted(lightHit.geometricNormal, -frame.toWorld(bs.wi));
        if (le.isBlack()) continue;
        const float w =
            bs.isSpecular()
                ? 1.0f
                : weight(nBsdf, bs.pdf, nLight,
                         selector.pmf(*light, hit.position) * light->pdf(hit.position, lightHit));
        radiance += bs.weight * le * (w / nBsdf);
    }
    return radiance;
}

}  // namespace rr
