// The `two_stage` estimator and integrator as scenes name them (configs/README.md).
#include "config/json_reader.h"
#include "render/technique_registry.h"
#include "techniques/two_stage/two_stage_decisions.h"
#include "techniques/two_stage/two_stage_integrator.h"

namespace rr::two_stage {

namespace {

constexpr int64_t kMaxSamples = 4096;

TwoStageSettings readEstimatorSettings(ObjectReader& json) {
    TwoStageSettings s;
    s.samples = static_cast<uint32_t>(json.getInt("samples", 1, Range::closed(1, kMaxSamples)));
    // The paper splits as many times as it takes samples; more simulates wavelet importance
    // sampling (fig. 12).
    if (json.has("splits"))
        s.splits =
            static_cast<uint32_t>(json.getInt("splits", 0, Range::closed(0, 64 * kMaxSamples)));
    s.peaks = json.getChoice("peaks", {"analytic", "bsdf"}, "analytic") == "bsdf"
                  ? PeakSource::BsdfSamples
                  : PeakSource::Analytic;
    return s;
}

std::unique_ptr<DirectLightingEstimator> makeEstimator(ObjectReader& json) {
    return std::make_unique<TwoStageEstimator>(readEstimatorSettings(json));
}

BuiltIntegrator makeIntegrator(ObjectReader& json, const IntegratorContext&) {
    TwoStageIntegratorSettings s;
    s.estimator = readEstimatorSettings(json);
    const std::string allocation =
        json.getChoice("allocation", {"fixed", "variable", "variable_rerender"}, "fixed");
    if (allocation == "fixed") {
        for (const char* key : {"pilot_pixels", "band_rows"})
            if (json.has(key))
                json.fail(key, std::string("\"") + key + "\" applies to variable allocation");
        return withUniformPasses(std::make_unique<TwoStageIntegrator>(s));
    }
    s.allocation = allocation == "variable" ? Allocation::Variable : Allocation::VariableRerender;
    s.pilotPixels =
        static_cast<uint32_t>(json.getInt("pilot_pixels", 1024, Range::closed(1, 1 << 24)));
    s.bandRows = static_cast<int>(json.getInt("band_rows", 16, Range::closed(1, 16384)));
    auto integrator = std::make_unique<TwoStageIntegrator>(s);
    TwoStageIntegrator* raw = integrator.get();
    return BuiltIntegrator{std::move(integrator),
                           [raw](const ScheduleInputs& in) { return raw->schedule(in); }};
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addEstimator("two_stage", makeEstimator);
    registry.addDecisions(kDecisions);
    registry.addIntegrator("two_stage", makeIntegrator, /*rendersMedia=*/false);
}

}  // namespace rr::two_stage
