#include "app/command_line.h"

#include "loader/factories.h"
#include "render/renderer.h"

namespace rr {

void addSceneOptions(CLI::App* command, RenderCommandOptions& o) {
    command->add_option("scene", o.scene, "scene JSON file")->required();
    std::string types;
    for (const std::string& type : techniqueRegistry().integratorTypes())
        types += (types.empty() ? "" : ", ") + type;
    command->add_option("--integrator", o.integrator, "integrator type (" + types + ")");
    command->add_option("--spp", o.spp, "samples per pixel (an upper bound with --time-limit)")
        ->check(CLI::Range(1u, kMaxSpp));
    command->add_option("--seed", o.seed, "random seed");
    command->add_option("--resolution", o.resolution, "image size WxH");
    command->add_option("--set", o.overrides, "override a scene value: /json/pointer=value")
        ->take_all();
}

void addRenderOptions(CLI::App* command, RenderCommandOptions& o) {
    addSceneOptions(command, o);
    command->add_option("--time-limit", o.timeLimit, "render in passes until SECONDS have passed")
        ->check(CLI::PositiveNumber);
    command->add_option("--threads", o.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    command->add_option("--out", o.out, "output EXR (default results/<scene>.exr)");
    command->add_option("--exposure", o.exposure, "preview exposure in stops");
    command->add_flag("!--no-preview", o.preview, "do not write the PNG preview");
}

}  // namespace rr
