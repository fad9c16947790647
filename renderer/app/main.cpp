// The renderer's command line. Subcommands: render, check.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/render_command.h"
#include "loader/factories.h"
#include "render/renderer.h"

namespace {

// Options that define the scene document: shared by `render` and `check`, so a check
// validates exactly what the same render command line would render.
void addSceneOptions(CLI::App* command, rr::RenderCommandOptions& o) {
    command->add_option("scene", o.scene, "scene JSON file")->required();
    std::string types;
    for (const std::string& type : rr::techniqueRegistry().integratorTypes())
        types += (types.empty() ? "" : ", ") + type;
    command->add_option("--integrator", o.integrator, "integrator type (" + types + ")");
    command->add_option("--spp", o.spp, "samples per pixel (an upper bound with --time-limit)")
        ->check(CLI::Range(1u, rr::kMaxSpp));
    command->add_option("--seed", o.seed, "random seed");
    command->add_option("--resolution", o.resolution, "image size WxH");
    command->add_option("--set", o.overrides, "override a scene value: /json/pointer=value")
        ->take_all();
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Research renderer for Monte Carlo importance-sampling reproductions"};
    app.require_subcommand(1);

    rr::RenderCommandOptions o;
    CLI::App* render = app.add_subcommand("render", "render a scene to EXR + PNG preview");
    addSceneOptions(render, o);
    render->add_option("--time-limit", o.timeLimit, "render in passes until SECONDS have passed")
        ->check(CLI::PositiveNumber);
    render->add_option("--threads", o.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    render->add_option("--out", o.out, "output EXR (default results/<scene>.exr)");
    render->add_option("--exposure", o.exposure, "preview exposure in stops");
    render->add_flag("!--no-preview", o.preview, "do not write the PNG preview");

    CLI::App* check = app.add_subcommand(
        "check", "load and validate a scene (assets included) without rendering; exit 2 if bad");
    addSceneOptions(check, o);
    check->add_flag("--json", o.json, "print the result as one JSON object");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }
    o.checkOnly = check->parsed();
    return rr::runRenderCommand(o);
}
