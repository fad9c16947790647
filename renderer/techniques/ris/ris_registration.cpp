// The `ris` estimator and integrator as scenes name them (configs/README.md).
#include "config/json_reader.h"
#include "techniques/ris/ris_decisions.h"
#include "techniques/ris/ris_integrator.h"

namespace rr::ris {

namespace {

constexpr double kMaxCount = 1024;

CandidateSource readSource(ObjectReader& json) {
    const std::string source = json.getChoice(
        "source",
        {"light", "light_proxy", "uniform_hemisphere", "cosine_hemisphere", "bsdf", "mixture"},
        "light");
    if (source == "uniform_hemisphere") return CandidateSource::UniformHemisphere;
    if (source == "cosine_hemisphere") return CandidateSource::CosineHemisphere;
    if (source == "bsdf") return CandidateSource::Bsdf;
    if (source == "mixture") return CandidateSource::Mixture;
    if (source == "light_proxy") return CandidateSource::LightProxy;
    return CandidateSource::Light;
}

// "candidates" (M) and "samples" (N): real numbers ≥ 1, rounded randomly when fractional.
CandidateCounts readCounts(ObjectReader& json) {
    return {json.getNumber("candidates", 1, Range::closed(1, kMaxCount)),
            json.getNumber("samples", 1, Range::closed(1, kMaxCount))};
}

std::unique_ptr<DirectLightingEstimator> makeEstimator(ObjectReader& json) {
    const CandidateSource source = readSource(json);
    return std::make_unique<RisEstimator>(source, readCounts(json));
}

// Keys that only some modes read: an error naming the key for the others.
void refuseKeys(ObjectReader& json, std::initializer_list<const char*> keys,
                const std::string& mode) {
    for (const char* key : keys)
        if (json.has(key))
            json.fail(key, std::string("\"") + key + "\" does not apply to mode \"" + mode + "\"");
}

RisSettings readSettings(ObjectReader& json) {
    RisSettings s;
    s.source = readSource(json);
    const std::string mode = json.getChoice("mode", {"fixed", "robust", "optimal"}, "robust");
    if (mode == "fixed") {
        refuseKeys(json, {"budget", "max_candidates", "pilot_rays", "pilot_samples", "costs"},
                   mode);
        s.counts = readCounts(json);
        return s;
    }
    refuseKeys(json, {"candidates", "samples"}, mode);
    s.choice = mode == "robust" ? CountChoice::Robust : CountChoice::Optimal;
    s.budget = json.getNumber("budget", Range::closed(1, kMaxCount));
    s.maxCandidates = json.getNumber("max_candidates", kMaxCount, Range::closed(1, kMaxCount));
    if (mode == "robust") refuseKeys(json, {"pilot_samples"}, mode);
    s.pilotSamples =
        static_cast<uint32_t>(json.getInt("pilot_samples", 16, Range::closed(2, 4096)));
    if (const Json* costs = json.rawOptional("costs")) {
        refuseKeys(json, {"pilot_rays"}, mode);
        ObjectReader c(*costs, json.pointerTo("costs"));
        s.costs = CandidateCosts{c.getNumber("t_x_ns", Range::positive()) * 1e-9,
                                 c.getNumber("t_y_ns", Range::positive()) * 1e-9};
        c.finish();
    }
    s.pilotRays =
        static_cast<uint32_t>(json.getInt("pilot_rays", 4096, Range::closed(16, 1 << 20)));
    return s;
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addEstimator("ris", makeEstimator);
    registry.addDecisions(kDecisions);
    registry.addIntegrator(
        "ris",
        [](ObjectReader& json, const IntegratorContext&) {
            auto ris = std::make_unique<RisIntegrator>(readSettings(json));
            RisIntegrator* integrator = ris.get();
            return BuiltIntegrator{std::move(ris), [integrator](const ScheduleInputs& in) {
                                       return integrator->schedule(in);
                                   }};
        },
        /*rendersMedia=*/false);
}

}  // namespace rr::ris
