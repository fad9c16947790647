// The renderer's command line. Subcommands: render, check, serve, keys.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "app/command_line.h"
#include "app/render_command.h"
#include "app/serve_command.h"
#include "loader/scene_keys.h"

int main(int argc, char** argv) {
    CLI::App app{"Research renderer for Monte Carlo importance-sampling reproductions"};
    app.require_subcommand(1);

    rr::RenderCommandOptions o;
    CLI::App* render = app.add_subcommand("render", "render a scene to EXR + PNG preview");
    rr::addRenderOptions(render, o);

    CLI::App* check = app.add_subcommand(
        "check", "load and validate a scene (assets included) without rendering; exit 2 if bad");
    rr::addSceneOptions(check, o);
    check->add_flag("--json", o.json, "print the result as one JSON object");

    rr::ServeOptions serveOptions;
    CLI::App* serve = app.add_subcommand(
        "serve",
        "render requests read from stdin, one JSON array of render arguments per line, "
        "keeping built scenes; one JSON reply per line on stdout");
    serve->add_option("--cached-scenes", serveOptions.cachedScenes, "built scenes kept")
        ->check(CLI::Range(0, 64));

    CLI::App* keys = app.add_subcommand(
        "keys",
        "print every key a scene file takes (name, kind, range, default, meaning) as JSON: the "
        "source of configs/README.md's key tables and configs/schema/scene.schema.json");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }
    if (serve->parsed()) return rr::runServeCommand(serveOptions);
    if (keys->parsed()) {
        std::printf("%s\n", rr::sceneKeys().describe().dump(1).c_str());
        return 0;
    }
    o.checkOnly = check->parsed();
    return rr::runRenderCommand(o);
}
