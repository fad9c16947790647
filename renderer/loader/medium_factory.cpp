#include "config/type_table.h"
#include "loader/factories.h"
#include "scene/media/henyey_greenstein.h"
#include "scene/media/homogeneous_medium.h"
#include "scene/media/isotropic_phase.h"

namespace rr {

namespace {

std::unique_ptr<PhaseFunction> makePhaseFunction(ObjectReader& json) {
    static const TypeTable<PhaseFunction> table{
        {"isotropic", [](ObjectReader&) { return std::make_unique<IsotropicPhase>(); }},
        {"henyey_greenstein",
         [](ObjectReader& j) {
             return std::make_unique<HenyeyGreenstein>(j.getFloat("g", Range::open(-1, 1)));
         }},
    };
    return buildByType(json, "phase function", table);
}

}  // namespace

std::unique_ptr<Medium> makeMedium(ObjectReader& json) {
    const Rgb sigmaA = json.getRgb("sigma_a", Rgb(0.0f), Range::nonNegative());
    const Rgb sigmaS = json.getRgb("sigma_s", Rgb(0.0f), Range::nonNegative());
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
