// The `two_stage` estimator and integrator as scenes name them (configs/README.md).
#include "config/json_reader.h"
#include "render/technique_registry.h"
#include "techniques/two_stage/two_stage_decisions.h"
#include "techniques/two_stage/two_stage_integrator.h"

namespace rr::two_stage {

namespace {

constexpr int64_t kMaxSamples = 4096;
const TwoStageIntegratorSettings kDefaults;

// The estimator's keys, which the integrator takes too.
std::vector<KeySpec> estimatorKeys() {
    return {key("samples")
                .integer(Range::closed(1, kMaxSamples))
                .byDefault(kDefaults.estimator.samples)
                .means("N, stage-2 samples per shading point"),
            key("splits")
                .integer(Range::closed(0, 64 * kMaxSamples))
                .defaultSays("N")
                .means("refinement splits per shading point (the paper: N; more simulates "
                       "wavelet importance sampling, fig. 12)"),
            key("peaks")
                .choice({"analytic", "bsdf"})
                .byDefault("analytic")
                .means("initial splits at the materials' own peaks, or at N/4 BSDF samples "
                       "whose f beats their leaf's corners (fig. 9)")};
}

const KeyTable kEstimatorKeys{
    "estimator/two_stage",
    "two-stage importance sampling of an environment map (Cline et al. 2006): per shading point "
    "a BSP partition of the lat-long map approximating Le·f (stage 1), then N samples warped "
    "through it to single texels (stage 2); one lat-long environment map, surfaces only",
    estimatorKeys()};

std::vector<KeySpec> integratorKeys() {
    std::vector<KeySpec> keys = estimatorKeys();
    keys.push_back(
        key("allocation")
            .choice({"fixed", "variable", "variable_rerender"})
            .byDefault("fixed")
            .means("N at every hit, or §5's per-pixel allocation n = (N/2)(1 + σ_p/σ_ave) "
                   "(eq. 9), with re-rendering of outliers (slightly biased)"));
    keys.push_back(key("pilot_pixels")
                       .integer(Range::closed(1, 1 << 24))
                       .byDefault(kDefaults.pilotPixels)
                       .means("variable allocations: pixels of the σ_ave preprocess"));
    keys.push_back(key("band_rows")
                       .integer(Range::closed(1, 16384))
                       .byDefault(kDefaults.bandRows)
                       .means("variable allocations: rows per band, scanned in serpentine "
                              "order"));
    return keys;
}

const KeyTable kIntegratorKeys{
    "integrator/two_stage",
    "direct lighting at the first hit by the `two_stage` estimator, one primary ray per pixel "
    "sample, with the samples per primary ray allocated as §5 allocates them",
    integratorKeys()};

TwoStageSettings readEstimatorSettings(ObjectReader& json) {
    TwoStageSettings s;
    s.samples = static_cast<uint32_t>(json.integer("samples"));
    if (json.has("splits")) s.splits = static_cast<uint32_t>(json.integer("splits"));
    s.peaks = json.choice("peaks") == "bsdf" ? PeakSource::BsdfSamples : PeakSource::Analytic;
    return s;
}

std::unique_ptr<DirectLightingEstimator> makeEstimator(ObjectReader& json) {
    return std::make_unique<TwoStageEstimator>(readEstimatorSettings(json));
}

BuiltIntegrator makeIntegrator(ObjectReader& json, const IntegratorContext&) {
    TwoStageIntegratorSettings s;
    s.estimator = readEstimatorSettings(json);
    const std::string allocation = json.choice("allocation");
    if (allocation == "fixed") {
        for (const char* key : {"pilot_pixels", "band_rows"})
            if (json.has(key))
                json.fail(key, std::string("\"") + key + "\" applies to variable allocation");
        return withUniformPasses(std::make_unique<TwoStageIntegrator>(s));
    }
    s.allocation = allocation == "variable" ? Allocation::Variable : Allocation::VariableRerender;
    s.pilotPixels = static_cast<uint32_t>(json.integer("pilot_pixels"));
    s.bandRows = static_cast<int>(json.integer("band_rows"));
    auto integrator = std::make_unique<TwoStageIntegrator>(s);
    TwoStageIntegrator* raw = integrator.get();
    return BuiltIntegrator{std::move(integrator),
                           [raw](const ScheduleInputs& in) { return raw->schedule(in); }};
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addEstimator("two_stage", kEstimatorKeys, makeEstimator);
    registry.addIntegrator("two_stage", kIntegratorKeys, makeIntegrator, /*rendersMedia=*/false);
    registry.addDecisions(kDecisions);
}

}  // namespace rr::two_stage
