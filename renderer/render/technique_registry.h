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
#include <vector>

#include "config/json_reader.h"
#include "integrators/direct_lighting_estimator.h"
#include "integrators/integrator.h"
#include "integrators/path_tracer.h"
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
};

// Uniform passes (render/uniform_passes.h): for integrators whose samples are independent.
BuiltIntegrator withUniformPasses(std::unique_ptr<SampleIntegrator> integrator);

class TechniqueRegistry;

// What an integrator's builder gets besides its JSON object: the path settings of the scene's
// "render" object, and the registry, to build an "estimator" the integrator takes.
struct IntegratorContext {
    const PathSettings& path;
    const TechniqueRegistry& registry;
};

class TechniqueRegistry {
  public:
    using IntegratorBuilder =
        std::function<BuiltIntegrator(ObjectReader&, const IntegratorContext&)>;
    using EstimatorBuilder = std::function<std::unique_ptr<DirectLightingEstimator>(ObjectReader&)>;

    // `rendersMedia`: the integrators of this type account for participating media (the
    // loader refuses a scene with media for any other).
    void addIntegrator(const std::string& type, IntegratorBuilder build, bool rendersMedia);
    void addEstimator(const std::string& type, EstimatorBuilder build);
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
    // Every decision: the standard ones, then the techniques' in registration order.
    std::span<const Decision> decisions() const { return decisions_; }

  private:
    struct IntegratorEntry {
        IntegratorBuilder build;
        bool rendersMedia = false;
    };
    std::map<std::string, IntegratorEntry> integrators_;
    std::map<std::string, EstimatorBuilder> estimators_;
    std::vector<Decision> decisions_{kStandardDecisions.begin(), kStandardDecisions.end()};
};

// Adds every technique folder's entries (generated from RENDERER_TECHNIQUES).
void registerTechniques(TechniqueRegistry& registry);

}  // namespace rr
