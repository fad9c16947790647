// The scene's "render" object: image size, samples, seed, sampler, reconstruction filter, path
// length, light selection.
#pragma once

#include <cstdint>

#include "config/json_reader.h"
#include "integrators/path_settings.h"
#include "render/reconstruction_filter.h"
#include "sampling/sampler.h"
#include "scene/light_selector.h"

namespace rr {

struct RenderSettings {
    int width = 256, height = 256;
    uint32_t spp = 16;
    uint32_t seed = 0;
    SamplerType sampler = SamplerType::Independent;
    FilterSettings filter;  // the box unless "filter" says otherwise
    LightSelection lightSelection = LightSelection::Power;
};

// Reads the "render" object; its path-length keys go to *path.
RenderSettings readRenderSettings(ObjectReader& json, PathSettings* path);

// The keys of the "render" object and of each filter type.
const KeyTable& renderKeys();
std::vector<std::pair<std::string, const KeyTable*>> filterTypeKeys();

}  // namespace rr
