#include "integrators/direct_lighting.h"
#include "integrators/light_sample_estimator.h"
#include "integrators/path_tracer.h"
#include "loader/factories.h"

namespace rr {

namespace {

KeySpec lightSamplesKey() {
    return key("light_samples")
        .integer(Range::closed(1, 1024))
        .byDefault(1)
        .means("light samples per estimate");
}

const KeyTable kPathKeys{
    "integrator/path",
    "all light transport by BSDF and phase-function sampling only: light counts where a path "
    "hits an emitter (point lights are never hit)",
    {}};

const KeyTable kPathMisKeys{
    "integrator/path_mis",
    "all light transport: next-event estimation at every non-specular surface vertex and every "
    "medium vertex by a direct-lighting estimator, plus BSDF or phase sampling",
    {estimatorKey()}};

const KeyTable kDirectKeys{
    "integrator/direct",
    "emission seen by the camera plus direct lighting at the first hit; no participating media",
    {key("strategy")
         .choice({"mis", "light", "bsdf"})
         .byDefault("mis")
         .means("a core estimator by name (not with `estimator`)"),
     lightSamplesKey(),
     key("estimator")
         .oneOf("estimator")
         .optional()
         .means("any estimator object (not with `strategy`, `light_samples`)"),
     key("bsdf_samples")
         .integer(Range::closed(1, 1024))
         .byDefault(1)
         .means("the integrator's own BSDF samples per pixel sample (traced unless the "
                "estimator covers all direct light)")}};

const KeyTable kMisKeys{
    "estimator/mis",
    "light samples (a light by `/render/light_selection`, a point on it), each combined with "
    "the integrator's BSDF or phase samples by the power heuristic with sample counts",
    {lightSamplesKey()}};

const KeyTable kLightKeys{
    "estimator/light",
    "light samples only, each counted in full; the emission the integrator's BSDF samples find "
    "at non-specular vertices is left out (counted once, here)",
    {lightSamplesKey()}};

const KeyTable kBsdfKeys{
    "estimator/bsdf",
    "no light samples: only the integrator's own BSDF or phase samples find emission, counted "
    "in full (`path_mis` with it renders exactly what `path` renders)",
    {}};

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
        const std::string strategy = json.choice("strategy");
        estimator =
            makeCoreEstimator(strategy, static_cast<uint32_t>(json.integer("light_samples")));
    }
    const auto bsdfSamples = static_cast<uint32_t>(json.integer("bsdf_samples"));
    return withUniformPasses(std::make_unique<DirectLighting>(std::move(estimator), bsdfSamples));
}

TechniqueRegistry coreRegistry() {
    TechniqueRegistry r;
    r.addIntegrator(
        "path", kPathKeys,
        [](ObjectReader&, const IntegratorContext& c) {
            return withUniformPasses(std::make_unique<PathTracer<>>(
                "path", c.path, std::make_unique<ScatteringOnlyEstimator>()));
        },
        /*rendersMedia=*/true);
    r.addIntegrator(
        "path_mis", kPathMisKeys,
        [](ObjectReader& json, const IntegratorContext& c) {
            return withUniformPasses(
                std::make_unique<PathTracer<>>("path_mis", c.path, c.readEstimator(json)));
        },
        /*rendersMedia=*/true);
    r.addIntegrator("direct", kDirectKeys, makeDirect, /*rendersMedia=*/false);
    r.addEstimator("mis", kMisKeys, [](ObjectReader& json) {
        return makeCoreEstimator("mis", static_cast<uint32_t>(json.integer("light_samples")));
    });
    r.addEstimator("light", kLightKeys, [](ObjectReader& json) {
        return makeCoreEstimator("light", static_cast<uint32_t>(json.integer("light_samples")));
    });
    r.addEstimator("bsdf", kBsdfKeys, [](ObjectReader&) { return makeCoreEstimator("bsdf", 1); });
    registerTechniques(r);
    return r;
}

}  // namespace

const TechniqueRegistry& techniqueRegistry() {
    static const TechniqueRegistry registry = coreRegistry();
    return registry;
}

}  // namespace rr
