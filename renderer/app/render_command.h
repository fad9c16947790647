// `renderer render SCENE.json [options]`: load, validate, render, write EXR + PNG preview.
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
};

// Exit status: 0 done, 1 failure while rendering or writing, 2 bad input (nothing written),
// 130 interrupted (a valid image of the samples reached was written).
int runRenderCommand(const RenderCommandOptions& options);

}  // namespace rr
