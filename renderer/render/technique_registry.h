// The integrators and direct-lighting estimators a scene can name, by type: the core ones
// (loader/integrator_factory.cpp) and those each technique folder registers, with the named
// decisions the techniques make (sampling/decisions.h). A technique is one
// folder, renderer/techniques/<name>/, whose registerTechnique(TechniqueRegistry&) adds its
// entries, and one line in renderer/techniques/CMakeLists.txt (RENDERER_TECHNIQUES), from which
// the build generates registerTechniques().
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "config/json_reader.h"
#include "integrators/direct_lighting_estimator.h"
#include "integrators/integrator.h"
#include "integrators/path_settings.h"
#include "render/reconstruction_filter.h"
#include "render/render_schedule.h"
#include "sampling/decisions.h"

namespace rr {

// What a schedule is made for: known once the scene is loaded and the command line read.
struct ScheduleInputs {
    const Scene& scene;
    int width = 0, height = 0;
    uint32_t spp = 0;  // with a time limit, an upper bound
    double timeLimit = 0;
    uint32_t seed = 0;  // the render's seed, for decisions a schedule draws itself
    // The scene's reconstruction filter. Any but the box splats samples into neighbouring
    // pixels (film.h), whose sums depend on how the samples are cut into rounds: the cut must
    // then follow a plan fixed by the settings, never by timing.
    FilterSettings filter;
    bool splattingFilm() const { return filter.type != FilterType::Box; }
};
using ScheduleMaker = std::function<std::unique_ptr<RenderSchedule>(const ScheduleInputs&)>;

// An integrator and how its samples are scheduled.
struct BuiltIntegrator {
    std::unique_ptr<Integrator> integrator;
    ScheduleMaker schedule;
    // The schedule is uniform passes (withUniformPasses): every pixel gets the same samples,
    // so a technique that allocates samples per pixel (PMC-IP) may schedule it instead.
    bool uniformPasses = false;
};

// Uniform passes (render/uniform_passes.h): for integrators whose samples are independent.
BuiltIntegrator withUniformPasses(std::unique_ptr<SampleIntegrator> integrator);

class TechniqueRegistry;

// What an integrator's builder gets besides its JSON object: the path settings of the scene's
// "render" object, and the registry, to build an "estimator" the integrator takes.
struct IntegratorContext {
    const PathSettings& path;
    const TechniqueRegistry& registry;

    // The integrator's "estimator" object, of any registered estimator type, as `path_mis`
    // reads it: absent, `mis` with one light sample. Its key table must declare estimatorKey().
    std::unique_ptr<DirectLightingEstimator> readEstimator(ObjectReader& json) const;
};

// The declaration of the "estimator" key that readEstimator reads.
KeySpec estimatorKey();

class TechniqueRegistry {
  public:
    using IntegratorBuilder =
        std::function<BuiltIntegrator(ObjectReader&, const IntegratorContext&)>;
    using EstimatorBuilder = std::function<std::unique_ptr<DirectLightingEstimator>(ObjectReader&)>;

    // `keys`: the type's key table (config/key_table.h), which the builder reads through and
    // from which the docs and the scene schema are generated; it must outlive the registry.
    // `rendersMedia`: the integrators of this type account for participating media (the
    // loader refuses a scene with media for any other).
    void addIntegrator(const std::string& type, const KeyTable& keys, IntegratorBuilder build,
                       bool rendersMedia);
    void addEstimator(const std::string& type, const KeyTable& keys, EstimatorBuilder build);
    // The table of an object inside an integrator's or estimator's (a key of kind Object
    // refers to it by name), for the catalogue.
    void addObjectKeys(const KeyTable& keys) { objectKeys_.push_back(&keys); }
    // The decisions a technique makes besides the standard ones. Their ids are hashed into
    // every coordinate, so two decisions sharing one would draw the same coordinates:
    // std::logic_error for an id or a name already taken, by a standard decision or another
    // technique's, and for a dimension count other than 1 or 2.
    void addDecisions(std::span<const Decision> decisions);

    // From a JSON object with a "type" key; ConfigError naming the pointer for an unknown
    // type or any bad or unknown key.
    BuiltIntegrator makeIntegrator(ObjectReader& json, const PathSettings& path) const;
    std::unique_ptr<DirectLightingEstimator> makeEstimator(ObjectReader& json) const;
    bool rendersMedia(const std::string& integratorType) const;
    // The integrator types that render media, for messages.
    std::vector<std::string> mediaIntegrators() const;
    // Every integrator type, in order.
    std::vector<std::string> integratorTypes() const;
    // Each type's key table, for the catalogue of scene keys.
    std::vector<std::pair<std::string, const KeyTable*>> integratorKeys() const;
    std::vector<std::pair<std::string, const KeyTable*>> estimatorKeys() const;
    const std::vector<const KeyTable*>& objectKeys() const { return objectKeys_; }
    // Every decision: the standard ones, then the techniques' in registration order.
    std::span<const Decision> decisions() const { return decisions_; }

  private:
    struct IntegratorEntry {
        IntegratorBuilder build;
        const KeyTable* keys = nullptr;
        bool rendersMedia = false;
    };
    struct EstimatorEntry {
        EstimatorBuilder build;
        const KeyTable* keys = nullptr;
    };
    std::map<std::string, IntegratorEntry> integrators_;
    std::map<std::string, EstimatorEntry> estimators_;
    std::vector<const KeyTable*> objectKeys_;
    std::vector<Decision> decisions_{kStandardDecisions.begin(), kStandardDecisions.end()};
};

// Adds every technique folder's entries (generated from RENDERER_TECHNIQUES).
void registerTechniques(TechniqueRegistry& registry);

}  // namespace rr
