#include "render/technique_registry.h"

#include <cstring>
#include <stdexcept>

#include "config/type_table.h"
#include "integrators/light_sample_estimator.h"
#include "render/uniform_passes.h"

namespace rr {

BuiltIntegrator withUniformPasses(std::unique_ptr<SampleIntegrator> integrator) {
    SampleIntegrator* samples = integrator.get();
    return {std::move(integrator),
            [samples](const ScheduleInputs& in) {
                samples->beginImage(in.width, in.height, /*iterated=*/false);
                return std::make_unique<UniformPasses>(in.scene, *samples, in.width, in.height,
                                                       in.spp, in.timeLimit, in.splattingFilm());
            },
            /*uniformPasses=*/true};
}

KeySpec estimatorKey() {
    return key("estimator")
        .oneOf("estimator")
        .defaultSays(R"(`{"type": "mis"}`)")
        .means("the direct-lighting estimator of next-event estimation");
}

std::unique_ptr<DirectLightingEstimator> IntegratorContext::readEstimator(
    ObjectReader& json) const {
    const Json* e = json.rawOptional("estimator");
    if (!e) return std::make_unique<LightSampleEstimator>(1, true);
    ObjectReader ej(*e, json.pointerTo("estimator"));
    return registry.makeEstimator(ej);
}

void TechniqueRegistry::addIntegrator(const std::string& type, const KeyTable& keys,
                                      IntegratorBuilder build, bool rendersMedia) {
    if (!integrators_.emplace(type, IntegratorEntry{std::move(build), &keys, rendersMedia}).second)
        throw std::logic_error("integrator type \"" + type + "\" registered twice");
}

void TechniqueRegistry::addEstimator(const std::string& type, const KeyTable& keys,
                                     EstimatorBuilder build) {
    if (!estimators_.emplace(type, EstimatorEntry{std::move(build), &keys}).second)
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
    const IntegratorEntry& entry = entryByType(json, "integrator", integrators_);
    json.addKeys(*entry.keys);
    BuiltIntegrator built = entry.build(json, IntegratorContext{path, *this});
    json.finish();
    built.integrator->setReadParameters(json.values());
    return built;
}

std::unique_ptr<DirectLightingEstimator> TechniqueRegistry::makeEstimator(
    ObjectReader& json) const {
    const EstimatorEntry& entry = entryByType(json, "direct-lighting estimator", estimators_);
    json.addKeys(*entry.keys);
    std::unique_ptr<DirectLightingEstimator> estimator = entry.build(json);
    json.finish();
    estimator->setReadParameters(json.values());
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

std::vector<std::pair<std::string, const KeyTable*>> TechniqueRegistry::integratorKeys() const {
    return typeKeys(integrators_);
}

std::vector<std::pair<std::string, const KeyTable*>> TechniqueRegistry::estimatorKeys() const {
    return typeKeys(estimators_);
}

std::vector<std::string> TechniqueRegistry::integratorTypes() const {
    std::vector<std::string> types;
    for (const auto& entry : integrators_)
        types.push_back(entry.first);
    return types;
}

}  // namespace rr
