// The `pmc_ip` integrator and the `pmc_hi` estimator as scenes name them (configs/README.md).
#include "config/json_reader.h"
#include "render/technique_registry.h"
#include "techniques/pmc/pmc_decisions.h"
#include "techniques/pmc/pmc_hi_estimator.h"
#include "techniques/pmc/pmc_ip_integrator.h"

namespace rr::pmc {

namespace {

const PmcIpSettings kIpDefaults;
const PmcHiSettings kHiDefaults;

const KeyTable kPmcIpKeys{
    "integrator/pmc_ip",
    "what its inner `integrator` estimates, with the samples per pixel chosen by population "
    "Monte Carlo on the image plane (Lai et al. 2007 §4); no participating media",
    {key("integrator")
         .oneOf("integrator")
         .means("renders the samples: an integrator whose pixel samples are independent and "
                "scheduled in uniform passes (`path`, `path_mis`, `direct`, `ris`, `two_stage` "
                "with fixed allocation)"),
     key("initial_spp")
         .integer(Range::closed(2, 1 << 16))
         .byDefault(kIpDefaults.initialSpp)
         .means("samples per pixel of the uniform initial image (α needs a variance)"),
     key("iteration_spp")
         .integer(Range::closed(1, 1 << 16))
         .byDefault(kIpDefaults.iterationSpp)
         .means("mean samples per pixel of each adaptive iteration"),
     key("epsilon")
         .number(Range::open(0, 1))
         .byDefault(kIpDefaults.epsilon)
         .means("the uniform (defensive) share of α"),
     key("image")
         .choice({"iterations", "pooled"})
         .defaultSays("`\"iterations\"` (`\"pooled\"` with `known_variance_spp`)")
         .means("the unweighted mean of the iterations' unbiased estimates, or every sample at "
                "once weighted by 1/its pixel's count (the paper's reading, biased)"),
     key("known_variance_spp")
         .integer(Range::closed(0, 1 << 16))
         .byDefault(kIpDefaults.knownVarianceSpp)
         .means("> 0: instead of PMC-IP, the best static allocation n ∝ σ/√tvi with σ² from a "
                "pilot of this many spp (a bound); not with the iteration keys")}};

const KeyTable kPmcHiKeys{
    "estimator/pmc_hi",
    "population Monte Carlo for the hemispheric integral (Lai et al. 2007 §5): per shading "
    "point, populations from a mixture of BSDF sampling, each light's sampling and a cone, "
    "adapted between iterations (eq. 8, 9); area and infinite lights, surfaces only",
    {key("samples")
         .integer(Range::closed(0, PmcHiEstimator::kMaxPopulation))
         .byDefault(kHiDefaults.samples)
         .means("N per iteration; 0: twice the components (2m)"),
     key("iterations")
         .integer(Range::closed(1, 16))
         .byDefault(kHiDefaults.iterations)
         .means("populations per shading point; the estimate is their unweighted mean"),
     key("cone_share")
         .number(Range{0, 1, false, true})
         .byDefault(kHiDefaults.coneShare)
         .means("α of the cone after the first adaptation that found something"),
     key("floor")
         .number(Range::open(0, 0.5))
         .byDefault(kHiDefaults.floor)
         .means("least α of the BSDF and of each light, with floor × (lights + 1) < 1"),
     key("light_components")
         .choice({"auto", "each", "one"})
         .byDefault("auto")
         .means("one component per light (`each`; `auto` up to 16 lights) or one for all "
                "(the integrator's light sampling, §5.1)"),
     key("alpha_maps")
         .boolean()
         .byDefault(kHiDefaults.alphaMaps)
         .means("write the mixture weights α^(T) at first hits as `pmc_hi.alpha.*` channels "
                "(fig. 7)"),
     key("feedback")
         .boolean()
         .byDefault(kHiDefaults.feedback)
         .means("§6.1, under `pmc_ip` only: a first hit starts from its pixel's mean α^(T) "
                "over the earlier PMC-IP iterations")}};

// "integrator": the integrator that renders the pixel samples; its samples must be
// independent and scheduled in uniform passes, for PMC-IP chooses how many each pixel gets.
std::unique_ptr<SampleIntegrator> readPixelIntegrator(ObjectReader& json,
                                                      const IntegratorContext& context) {
    ObjectReader inner(json.raw("integrator"), json.pointerTo("integrator"));
    BuiltIntegrator built = context.registry.makeIntegrator(inner, context.path);
    auto* samples = dynamic_cast<SampleIntegrator*>(built.integrator.get());
    if (!samples)
        json.fail("integrator", built.integrator->name() +
                                    " chooses its own samples per pixel; pmc_ip needs an "
                                    "integrator whose pixel samples are independent");
    // A sample integrator with a schedule of its own (two_stage's variable allocations)
    // chooses the samples per pixel itself, which pmc_ip would replace.
    if (!built.uniformPasses)
        json.fail("integrator", "pmc_ip chooses the samples per pixel; " +
                                    built.integrator->name() +
                                    " here schedules its own (give it a fixed allocation)");
    built.integrator.release();
    return std::unique_ptr<SampleIntegrator>(samples);
}

BuiltIntegrator makePmcIp(ObjectReader& json, const IntegratorContext& context) {
    PmcIpSettings s;
    s.knownVarianceSpp = static_cast<uint32_t>(json.integer("known_variance_spp"));
    if (s.knownVarianceSpp > 0) {
        // The static allocation has no iterations to adapt.
        for (const char* key : {"initial_spp", "iteration_spp", "epsilon"})
            if (json.has(key))
                json.fail(key, "does not apply with known_variance_spp (a static allocation)");
    }
    s.initialSpp = static_cast<uint32_t>(json.integer("initial_spp"));
    s.iterationSpp = static_cast<uint32_t>(json.integer("iteration_spp"));
    s.epsilon = json.number("epsilon");
    // The static allocation renders one iteration: its image pools it.
    const char* image = s.knownVarianceSpp > 0 ? "pooled" : "iterations";
    s.image = json.getChoice("image", json.spec("image").choices, image) == "pooled"
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
    s.samples = static_cast<uint32_t>(json.integer("samples"));
    s.iterations = static_cast<uint32_t>(json.integer("iterations"));
    s.coneShare = json.number("cone_share");
    // A zero floor would let the BSDF and a light both die: no support where they cover.
    s.floor = json.number("floor");
    const std::string lights = json.choice("light_components");
    s.lightComponents = lights == "each"  ? LightComponents::Each
                        : lights == "one" ? LightComponents::One
                                          : LightComponents::Auto;
    s.alphaMaps = json.boolean("alpha_maps");
    s.feedback = json.boolean("feedback");
    return std::make_unique<PmcHiEstimator>(s);
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addIntegrator("pmc_ip", kPmcIpKeys, makePmcIp, /*rendersMedia=*/false);
    registry.addEstimator("pmc_hi", kPmcHiKeys, makePmcHi);
    registry.addDecisions(kDecisions);
}

}  // namespace rr::pmc
