// `renderer render SCENE.json [options]`: load, validate, render, write EXR + PNG preview.
// `renderer check SCENE.json [--set ...]`: the same loading and validation, nothing rendered.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "loader/scene_cache.h"

namespace rr {

struct RenderCommandOptions {
    std::string scene;
    std::optional<std::string> integrator;
    std::optional<uint32_t> spp;
    double timeLimit = 0;
    std::optional<uint32_t> seed;
    int threads = 0;
    std::optional<std::string> resolution;  // "WxH"
    std::optional<std::string> out;
    std::vector<std::string> overrides;  // "/json/pointer=value"
    float exposure = 0;
    bool preview = true;
    bool checkOnly = false;  // `renderer check`: load and validate, render nothing
    bool json = false;       // `renderer check --json`: the result as one JSON object on stdout
};

// Where a render reports and what it may reuse. Messages (errors, warnings, the summary) are
// one line each, to stderr unless `report` is set; `renderer serve` passes its scene cache and
// collects the lines for its reply.
using Reporter = std::function<void(const std::string&)>;
struct RenderEnvironment {
    SceneCache* scenes = nullptr;
    Reporter report;
    bool progressBar = true;  // drawn on a terminal only
};

// Exit status: 0 done, 1 failure while rendering or writing, 2 bad input (nothing written),
// 130 interrupted (a valid image of the samples reached was written). With checkOnly: 0 valid,
// 2 bad input; with json as well, stdout holds {"valid": true, "integrator", "resolution",
// "spp", "features", "sceneSha256"} or {"valid": false, "error": "invalid" | "missing_asset",
// "pointer", "message"}.
int runRenderCommand(const RenderCommandOptions& options,
                     const RenderEnvironment& environment = {});

}  // namespace rr
