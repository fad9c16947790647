// Reads a scene document (see configs/README.md) into a Scene, its render settings and its
// integrator. Every problem is a ConfigError naming the JSON pointer; nothing is rendered or
// written before the whole document has been validated.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "config/json_document.h"
#include "integrators/integrator.h"
#include "loader/asset_resolver.h"
#include "loader/render_settings_reader.h"
#include "loader/scene_cache.h"
#include "render/technique_registry.h"
#include "scene/scene.h"

namespace rr {

struct LoadedScene {
    std::shared_ptr<const Scene> scene;  // immutable; shared with a SceneCache
    std::unique_ptr<Integrator> integrator;
    ScheduleMaker schedule;  // how the integrator's samples are scheduled
    RenderSettings render;
    // The integrator's preprocess over the built scene (Integrator::prepare, e.g. two-stage
    // sampling's summed-area table), outside the timed render: reported so that comparisons
    // can charge it.
    double prepareSeconds = 0;

    // The film's reconstruction filter: the scene's, or the box when the integrator forms the
    // image from its own record of the samples (Integrator::formsOwnImage) and the film only
    // counts them.
    ReconstructionFilter filmFilter() const;
    // The inputs of the integrator's schedule for this scene, at `spp` (with a time limit, an
    // upper bound) and the scene's size and seed.
    ScheduleInputs scheduleInputs(uint32_t spp, double timeLimit) const;
};

// With a cache, a scene built before from the same scene objects, resolution, light selection
// and asset files is reused, and a newly built one is added: the integrator is always built
// afresh, so renders share nothing that a render changes.
LoadedScene loadScene(const Json& document, const AssetResolver& assets,
                      SceneCache* cache = nullptr);

// The document without what changes only how its image is estimated, never the image's
// expectation: the keys the scene's key tables declare estimand-neutral (the description; the
// render settings spp, seed, sampler, light_selection, rr_depth, rr_survival, rr_threshold;
// an environment light's `sampling`: loader/scene_keys.cpp gathers the tables). Two documents
// with the same estimand converge to the same image (the harness keys its references by it).
// The integrator stays: `direct` and `path` estimate different images.
Json estimandOf(const Json& document);

}  // namespace rr
