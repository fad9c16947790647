// The `ris` estimator and integrator as scenes name them (configs/README.md).
#include "config/json_reader.h"
#include "techniques/ris/ris_decisions.h"
#include "techniques/ris/ris_integrator.h"

namespace rr::ris {

namespace {

constexpr double kMaxCount = 1024;
const RisSettings kDefaults;

KeySpec sourceKey() {
    return key("source")
        .choice(
            {"light", "light_proxy", "uniform_hemisphere", "cosine_hemisphere", "bsdf", "mixture"})
        .byDefault("light")
        .means("where candidates come from (see the `ris` estimator's description)");
}

KeySpec countKey(const char* name, const char* meaning) {
    return key(name).number(Range::closed(1, kMaxCount)).byDefault(1.0).means(meaning);
}

const KeyTable kEstimatorKeys{
    "estimator/ris",
    "resampled importance sampling (eq. 1): N samples per shading point, each keeping one of M "
    "fresh candidates from `source` with probability ∝ ĝ/p, and only then tracing its shadow "
    "ray; fractional M and N are rounded randomly per shading point",
    {sourceKey(), countKey("candidates", "M, candidates per sample"),
     countKey("samples", "N, samples per shading point")}};

const KeyTable kIntegratorKeys{
    "integrator/ris",
    "emission seen by the camera plus direct lighting at the first hit by the `ris` estimator, "
    "with M and N chosen as the paper chooses them; no participating media",
    {sourceKey(),
     key("mode")
         .choice({"fixed", "robust", "optimal"})
         .byDefault("robust")
         .means("`fixed`: M and N as given; `robust` (§4.3, eq. 4): M = T_Y/T_X, N from the "
                "budget; `optimal` (§4.2, eq. 3): M per pixel from a pilot, N from the budget"),
     countKey("candidates", "`fixed`: M"), countKey("samples", "`fixed`: N"),
     key("budget")
         .number(Range::closed(1, kMaxCount))
         .defaultSays("required for `robust`, `optimal`")
         .means("the time of this many plain light samples per shading point: M N T_X + N T_Y "
                "= budget·(T_X + T_Y)"),
     key("costs")
         .object("ris_costs")
         .optional()
         .means("T_X and T_Y given, instead of measured by a pilot inside the timed render "
                "(which makes M, N and the image vary from run to run)"),
     key("pilot_rays")
         .integer(Range::closed(16, 1 << 20))
         .byDefault(kDefaults.pilotRays)
         .means("primary rays of the cost pilot (the paper: \"a few thousand\")"),
     key("pilot_samples")
         .integer(Range::closed(2, 4096))
         .byDefault(kDefaults.pilotSamples)
         .means("`optimal`: light samples per pixel for the terms e1, e2, e3 of eq. (2)"),
     key("max_candidates")
         .number(Range::closed(1, kMaxCount))
         .byDefault(kDefaults.maxCandidates)
         .means("the largest M `robust` and `optimal` may choose")}};

const KeyTable kCostKeys{
    "ris_costs",
    "the costs of a candidate and of a finished sample",
    {key("t_x_ns")
         .number(Range::positive())
         .means("T_X: draw a candidate and evaluate ĝ, in nanoseconds"),
     key("t_y_ns")
         .number(Range::positive())
         .means(
             "T_Y: finish a chosen sample (its shadow ray, or the ray that finds its emission)")}};

CandidateSource readSource(ObjectReader& json) {
    const std::string source = json.choice("source");
    if (source == "uniform_hemisphere") return CandidateSource::UniformHemisphere;
    if (source == "cosine_hemisphere") return CandidateSource::CosineHemisphere;
    if (source == "bsdf") return CandidateSource::Bsdf;
    if (source == "mixture") return CandidateSource::Mixture;
    if (source == "light_proxy") return CandidateSource::LightProxy;
    return CandidateSource::Light;
}

// "candidates" (M) and "samples" (N): real numbers ≥ 1, rounded randomly when fractional.
CandidateCounts readCounts(ObjectReader& json) {
    return {json.number("candidates"), json.number("samples")};
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
    const std::string mode = json.choice("mode");
    if (mode == "fixed") {
        refuseKeys(json, {"budget", "max_candidates", "pilot_rays", "pilot_samples", "costs"},
                   mode);
        s.counts = readCounts(json);
        return s;
    }
    refuseKeys(json, {"candidates", "samples"}, mode);
    s.choice = mode == "robust" ? CountChoice::Robust : CountChoice::Optimal;
    s.budget = json.number("budget");
    s.maxCandidates = json.number("max_candidates");
    if (mode == "robust") refuseKeys(json, {"pilot_samples"}, mode);
    s.pilotSamples = static_cast<uint32_t>(json.integer("pilot_samples"));
    if (const Json* costs = json.rawOptional("costs")) {
        refuseKeys(json, {"pilot_rays"}, mode);
        ObjectReader c(*costs, json.pointerTo("costs"), kCostKeys);
        s.costs = CandidateCosts{c.number("t_x_ns") * 1e-9, c.number("t_y_ns") * 1e-9};
        c.finish();
    }
    s.pilotRays = static_cast<uint32_t>(json.integer("pilot_rays"));
    return s;
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addEstimator("ris", kEstimatorKeys, makeEstimator);
    registry.addObjectKeys(kCostKeys);
    registry.addDecisions(kDecisions);
    registry.addIntegrator(
        "ris", kIntegratorKeys,
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
