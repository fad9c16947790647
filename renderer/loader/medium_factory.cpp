#include "config/type_table.h"
#include "loader/factories.h"
#include "scene/media/henyey_greenstein.h"
#include "scene/media/homogeneous_medium.h"
#include "scene/media/isotropic_phase.h"

namespace rr {

namespace {

const KeyTable kMediumKeys{
    "medium",
    "a homogeneous participating medium",
    {key("sigma_a").colour().byDefault(0.0).means("absorption coefficient σa per unit length"),
     key("sigma_s").colour().byDefault(0.0).means(
         "scattering coefficient σs per unit length; both 0: a vacuum"),
     key("phase").oneOf("phase").defaultSays("isotropic").means("the phase function")}};

const KeyTable kIsotropicKeys{"phase/isotropic", "scatters uniformly over the sphere", {}};

const KeyTable kHenyeyGreensteinKeys{
    "phase/henyey_greenstein",
    "Henyey–Greenstein: g > 0 scatters forward, g < 0 backward",
    {key("g").number(Range::open(-1, 1)).means("the mean cosine of the scattering angle")}};

std::unique_ptr<PhaseFunction> makePhaseFunction(ObjectReader& json) {
    return buildByType(json, "phase function", phaseTypes());
}

}  // namespace

const TypeTable<PhaseFunction>& phaseTypes() {
    static const TypeTable<PhaseFunction> table{
        {"isotropic",
         {[](ObjectReader&) { return std::make_unique<IsotropicPhase>(); }, &kIsotropicKeys}},
        {"henyey_greenstein",
         {[](ObjectReader& j) { return std::make_unique<HenyeyGreenstein>(j.real("g")); },
          &kHenyeyGreensteinKeys}},
    };
    return table;
}

const KeyTable& mediumKeys() {
    return kMediumKeys;
}

std::unique_ptr<Medium> makeMedium(ObjectReader& json) {
    json.addKeys(kMediumKeys);
    const Rgb sigmaA = json.colour("sigma_a");
    const Rgb sigmaS = json.colour("sigma_s");
    std::unique_ptr<PhaseFunction> phase;
    if (const Json* p = json.rawOptional("phase")) {
        ObjectReader pj(*p, json.pointerTo("phase"));
        phase = makePhaseFunction(pj);
    } else {
        phase = std::make_unique<IsotropicPhase>();
    }
    json.finish();
    return std::make_unique<HomogeneousMedium>(sigmaA, sigmaS, std::move(phase));
}

}  // namespace rr
