// Reads a scene document (see configs/README.md) into a Scene, its render settings and its
// integrator. Every problem is a ConfigError naming the JSON pointer; nothing is rendered or
// written before the whole document has been validated.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "integrators/integrator.h"
#include "loader/asset_resolver.h"
#include "loader/json_reader.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace rr {

struct RenderSettings {
    int width = 256, height = 256;
    uint32_t spp = 16;
    uint32_t seed = 0;
    SamplerType sampler = SamplerType::Independent;
    LightSelection lightSelection = LightSelection::Power;
};

struct LoadedScene {
    std::unique_ptr<Scene> scene;
    std::unique_ptr<Integrator> integrator;
    RenderSettings render;
};

// Parses JSON text; malformed input is a ConfigError at "/" naming line and column.
Json parseSceneText(const std::string& text, const std::string& sourceName);
Json readSceneFile(const std::filesystem::path& file);

// Applies `--set /json/pointer=value`: value is parsed as JSON, or taken as a string if it
// is not valid JSON. The parent of the pointer must exist.
void applyOverride(Json& document, const std::string& assignment);

LoadedScene loadScene(const Json& document, const AssetResolver& assets);

}  // namespace rr
