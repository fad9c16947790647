#include "integrators/direct_lighting.h"
#include "integrators/path_tracer.h"
#include "loader/factories.h"
#include "loader/type_table.h"
#include "techniques/tais/tais_integrator.h"

namespace rr {

std::unique_ptr<Integrator> makeIntegrator(ObjectReader& json, const PathSettings& path) {
    static const TypeTable<Integrator, const PathSettings&> table{
        {"path",
         [](ObjectReader&, const PathSettings& p) {
             return std::make_unique<PathTracer>(p, /*nextEventEstimation=*/false);
         }},
        {"path_mis",
         [](ObjectReader&, const PathSettings& p) {
             return std::make_unique<PathTracer>(p, /*nextEventEstimation=*/true);
         }},
        {"direct",
         [](ObjectReader& j, const PathSettings&) {
             DirectSettings s;
             const std::string strategy = j.getChoice("strategy", {"mis", "light", "bsdf"}, "mis");
             s.strategy = strategy == "light"  ? DirectStrategy::Light
                          : strategy == "bsdf" ? DirectStrategy::Bsdf
                                               : DirectStrategy::Mis;
             s.lightSamples =
                 static_cast<int>(j.getInt("light_samples", 1, Range::closed(1, 1024)));
             s.bsdfSamples = static_cast<int>(j.getInt("bsdf_samples", 1, Range::closed(1, 1024)));
             return std::make_unique<DirectLighting>(s);
         }},
        {"tais", tais::makeTaisIntegrator},
    };
    return buildByType(json, "integrator", table, path);
}

}  // namespace rr
