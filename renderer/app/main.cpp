// The renderer's command line. Subcommands: render.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/render_command.h"
#include "render/renderer.h"

int main(int argc, char** argv) {
    CLI::App app{"Research renderer for Monte Carlo importance-sampling reproductions"};
    app.require_subcommand(1);

    rr::RenderCommandOptions o;
    CLI::App* render = app.add_subcommand("render", "render a scene to EXR + PNG preview");
    render->add_option("scene", o.scene, "scene JSON file")->required();
    render->add_option("--integrator", o.integrator, "integrator type (path, path_mis, direct)");
    render->add_option("--spp", o.spp, "samples per pixel (an upper bound with --time-limit)")
        ->check(CLI::Range(1u, rr::kMaxSpp));
    render->add_option("--time-limit", o.timeLimit, "render in passes until SECONDS have passed")
        ->check(CLI::PositiveNumber);
    render->add_option("--seed", o.seed, "random seed");
    render->add_option("--threads", o.threads, "worker threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    render->add_option("--resolution", o.resolution, "image size WxH");
    render->add_option("--out", o.out, "output EXR (default results/<scene>.exr)");
    render->add_option("--set", o.overrides, "override a scene value: /json/pointer=value")
        ->take_all();
    render->add_option("--exposure", o.exposure, "preview exposure in stops");
    render->add_flag("!--no-preview", o.preview, "do not write the PNG preview");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }
    return rr::runRenderCommand(o);
}
