// The `pmc_ip` integrator and the `pmc_hi` estimator as scenes name them (configs/README.md).
#include "config/json_reader.h"
#include "render/technique_registry.h"
#include "techniques/pmc/pmc_decisions.h"
#include "techniques/pmc/pmc_hi_estimator.h"
#include "techniques/pmc/pmc_ip_integrator.h"

namespace rr::pmc {

namespace {

// "integrator": the integrator that renders the pixel samples; its samples must be
// independent, for PMC-IP chooses how many each pixel gets.
std::unique_ptr<SampleIntegrator> readPixelIntegrator(ObjectReader& json,
                                                      const IntegratorContext& context) {
    ObjectReader inner(json.raw("integrator"), json.pointerTo("integrator"));
    BuiltIntegrator built = context.registry.makeIntegrator(inner, context.path);
    auto* samples = dynamic_cast<SampleIntegrator*>(built.integrator.get());
    if (!samples)
        json.fail("integrator", built.integrator->name() +
                                    " chooses its own samples per pixel; pmc_ip needs an "
                                    "integrator whose pixel samples are independent");
    // two_stage's variable allocations are sample integrators with a schedule of their own,
    // which pmc_ip would replace.
    const nlohmann::json parameters = samples->parameters();
    if (parameters.value("allocation", "fixed") != "fixed")
        json.fail("integrator", "pmc_ip chooses the samples per pixel; give " +
                                    built.integrator->name() + " a fixed allocation");
    built.integrator.release();
    return std::unique_ptr<SampleIntegrator>(samples);
}

BuiltIntegrator makePmcIp(ObjectReader& json, const IntegratorContext& context) {
    PmcIpSettings s;
    s.knownVarianceSpp =
        static_cast<uint32_t>(json.getInt("known_variance_spp", 0, Range::closed(0, 1 << 16)));
    if (s.knownVarianceSpp > 0) {
        // The static allocation has no iterations to adapt.
        for (const char* key : {"initial_spp", "iteration_spp", "epsilon"})
            if (json.has(key))
                json.fail(key, "does not apply with known_variance_spp (a static allocation)");
    }
    s.initialSpp = static_cast<uint32_t>(json.getInt("initial_spp", 2, Range::closed(2, 1 << 16)));
    s.iterationSpp =
        static_cast<uint32_t>(json.getInt("iteration_spp", 4, Range::closed(1, 1 << 16)));
    s.epsilon = json.getNumber("epsilon", 0.01, Range::open(0, 1));
    // The static allocation renders one iteration: its image pools it.
    const char* image = s.knownVarianceSpp > 0 ? "pooled" : "iterations";
    s.image = json.getChoice("image", {"iterations", "pooled"}, image) == "pooled"
                  ? ImageEstimate::Pooled
                  : ImageEstimate::Iterations;
    if (s.knownVarianceSpp > 0 && s.image != ImageEstimate::Pooled)
        json.fail("image",
                  "the static allocation (known_variance_spp) renders one iteration, "
                  "whose image is \"pooled\"");
    auto integrator = std::make_unique<PmcIpIntegrator>(readPixelIntegrator(json, context), s);
    PmcIpIntegrator* raw = integrator.get();
    return BuiltIntegrator{std::move(integrator),
                           [raw](const ScheduleInputs& in) { return raw->schedule(in); }};
}

std::unique_ptr<DirectLightingEstimator> makePmcHi(ObjectReader& json) {
    PmcHiSettings s;
    s.samples = static_cast<uint32_t>(
        json.getInt("samples", 0, Range::closed(0, PmcHiEstimator::kMaxPopulation)));
    s.iterations = static_cast<uint32_t>(json.getInt("iterations", 2, Range::closed(1, 16)));
    s.coneShare = json.getNumber("cone_share", 0.2, Range{0, 1, false, true});
    // A zero floor would let the BSDF and a light both die: no support where they cover.
    s.floor = json.getNumber("floor", 0.05, Range::open(0, 0.5));
    const std::string lights = json.getChoice("light_components", {"auto", "each", "one"}, "auto");
    s.lightComponents = lights == "each"  ? LightComponents::Each
                        : lights == "one" ? LightComponents::One
                                          : LightComponents::Auto;
    s.alphaMaps = json.getBool("alpha_maps", false);
    s.feedback = json.getBool("feedback", false);
    return std::make_unique<PmcHiEstimator>(s);
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addIntegrator("pmc_ip", makePmcIp, /*rendersMedia=*/false);
    registry.addEstimator("pmc_hi", makePmcHi);
    registry.addDecisions(kDecisions);
}

}  // namespace rr::pmc
