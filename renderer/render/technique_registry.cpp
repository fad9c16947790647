#include "render/technique_registry.h"

#include <cstring>
#include <stdexcept>

#include "config/type_table.h"
#include "render/uniform_passes.h"

namespace rr {

BuiltIntegrator withUniformPasses(std::unique_ptr<SampleIntegrator> integrator) {
    SampleIntegrator* samples = integrator.get();
    return {std::move(integrator), [samples](const ScheduleInputs& in) {
                samples->beginImage(in.width, in.height, /*iterated=*/false);
                return std::make_unique<UniformPasses>(in.scene, *samples, in.width, in.height,
                                                       in.spp, in.timeLimit, in.splattingFilm());
            }};
}

void TechniqueRegistry::addIntegrator(const std::string& type, IntegratorBuilder build,
                                      bool rendersMedia) {
    if (!integrators_.emplace(type, IntegratorEntry{std::move(build), rendersMedia}).second)
        throw std::logic_error("integrator type \"" + type + "\" registered twice");
}

void TechniqueRegistry::addEstimator(const std::string& type, EstimatorBuilder build) {
    if (!estimators_.emplace(type, std::move(build)).second)
        throw std::logic_error("estimator type \"" + type + "\" registered twice");
}

void TechniqueRegistry::addDecisions(std::span<const Decision> decisions) {
    for (const Decision& d : decisions) {
        if (d.dimensions != 1 && d.dimensions != 2)
            throw std::logic_error("decision \"" + std::string(d.name) + "\" has " +
                                   std::to_string(d.dimensions) + " dimensions");
        for (const Decision& taken : decisions_)
            if (d.id == taken.id || std::strcmp(d.name, taken.name) == 0)
                throw std::logic_error("decision \"" + std::string(d.name) + "\" (id " +
                                       std::to_string(d.id) + ") clashes with \"" + taken.name +
                                       "\" (id " + std::to_string(taken.id) + ")");
        decisions_.push_back(d);
    }
}

BuiltIntegrator TechniqueRegistry::makeIntegrator(ObjectReader& json,
                                                  const PathSettings& path) const {
    BuiltIntegrator built =
        entryByType(json, "integrator", integrators_).build(json, IntegratorContext{path, *this});
    json.finish();
    return built;
}

std::unique_ptr<DirectLightingEstimator> TechniqueRegistry::makeEstimator(
    ObjectReader& json) const {
    std::unique_ptr<DirectLightingEstimator> estimator =
        entryByType(json, "direct-lighting estimator", estimators_)(json);
    json.finish();
    return estimator;
}

bool TechniqueRegistry::rendersMedia(const std::string& integratorType) const {
    const auto it = integrators_.find(integratorType);
    return it != integrators_.end() && it->second.rendersMedia;
}

std::vector<std::string> TechniqueRegistry::mediaIntegrators() const {
    std::vector<std::string> types;
    for (const auto& [type, entry] : integrators_)
        if (entry.rendersMedia) types.push_back(type);
    return types;
}

std::vector<std::string> TechniqueRegistry::integratorTypes() const {
    std::vector<std::string> types;
    for (const auto& entry : integrators_)
        types.push_back(entry.first);
    return types;
}

}  // namespace rr
