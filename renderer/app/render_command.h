// `renderer render SCENE.json [options]`: load, validate, render, write EXR + PNG preview.
// `renderer check SCENE.json [--set ...]`: the same loading and validation, nothing rendered.
#pragma once

#include <optional>
#include <string>
#include <vector>

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

// Exit status: 0 done, 1 failure while rendering or writing, 2 bad input (nothing written),
// 130 interrupted (a valid image of the samples reached was written). With checkOnly: 0 valid,
// 2 bad input; with json as well, stdout holds {"valid": true, "integrator", "resolution",
// "spp", "features", "sceneSha256"} or {"valid": false, "error": "invalid" | "missing_asset",
// "pointer", "message"}.
int runRenderCommand(const RenderCommandOptions& options);

}  // namespace rr
