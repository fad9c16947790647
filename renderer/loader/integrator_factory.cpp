#include "integrators/direct_lighting.h"
#include "integrators/light_sample_estimator.h"
#include "integrators/path_tracer.h"
#include "loader/factories.h"

namespace rr {

namespace {

// "light_samples": light samples per estimate.
uint32_t readLightSamples(ObjectReader& json) {
    return static_cast<uint32_t>(json.getInt("light_samples", 1, Range::closed(1, 1024)));
}

// `light`, `mis` or `bsdf` (which samples no light, whatever lightSamples says).
std::unique_ptr<DirectLightingEstimator> makeCoreEstimator(const std::string& strategy,
                                                           uint32_t lightSamples) {
    if (strategy == "bsdf") return std::make_unique<ScatteringOnlyEstimator>();
    return std::make_unique<LightSampleEstimator>(lightSamples, strategy == "mis");
}

// `direct`: "strategy" (with "light_samples") names a core estimator; "estimator" any one.
BuiltIntegrator makeDirect(ObjectReader& json, const IntegratorContext& context) {
    std::unique_ptr<DirectLightingEstimator> estimator;
    if (json.has("estimator")) {
        for (const char* key : {"strategy", "light_samples"})
            if (json.has(key))
                json.fail(key,
                          "give either \"strategy\" (and \"light_samples\") or "
                          "\"estimator\", not both");
        estimator = context.readEstimator(json);
    } else {
        const std::string strategy = json.getChoice("strategy", {"mis", "light", "bsdf"}, "mis");
        estimator = makeCoreEstimator(strategy, readLightSamples(json));
    }
    const auto bsdfSamples =
        static_cast<uint32_t>(json.getInt("bsdf_samples", 1, Range::closed(1, 1024)));
    return withUniformPasses(std::make_unique<DirectLighting>(std::move(estimator), bsdfSamples));
}

TechniqueRegistry coreRegistry() {
    TechniqueRegistry r;
    r.addIntegrator(
        "path",
        [](ObjectReader&, const IntegratorContext& c) {
            return withUniformPasses(std::make_unique<PathTracer<>>(
                "path", c.path, std::make_unique<ScatteringOnlyEstimator>()));
        },
        /*rendersMedia=*/true);
    r.addIntegrator(
        "path_mis",
        [](ObjectReader& json, const IntegratorContext& c) {
            return withUniformPasses(
                std::make_unique<PathTracer<>>("path_mis", c.path, c.readEstimator(json)));
        },
        /*rendersMedia=*/true);
    r.addIntegrator("direct", makeDirect, /*rendersMedia=*/false);
    for (const char* strategy : {"light", "bsdf", "mis"})
        r.addEstimator(strategy, [strategy](ObjectReader& json) {
            return makeCoreEstimator(strategy,
                                     std::string(strategy) == "bsdf" ? 1 : readLightSamples(json));
        });
    registerTechniques(r);
    return r;
}

}  // namespace

const TechniqueRegistry& techniqueRegistry() {
    static const TechniqueRegistry registry = coreRegistry();
    return registry;
}

}  // namespace rr
