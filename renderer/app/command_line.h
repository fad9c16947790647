// The options of `renderer render` and `renderer check`, defined once: `renderer serve` parses
// each request with the same definitions, so a served render is the render its arguments
// would give on the command line.
#pragma once

#include <CLI/CLI.hpp>

#include "app/render_command.h"

namespace rr {

// Options that define the scene document: shared by `render` and `check`, so a check
// validates exactly what the same render command line would render.
void addSceneOptions(CLI::App* command, RenderCommandOptions& o);
// The scene options and those of rendering and writing.
void addRenderOptions(CLI::App* command, RenderCommandOptions& o);

}  // namespace rr
