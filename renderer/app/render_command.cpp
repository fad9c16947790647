#include "app/render_command.h"

#include <tbb/info.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/interrupt.h"
#include "app/progress_bar.h"
#include "io/exr_io.h"
#include "io/png_preview.h"
#include "io/sha256.h"
#include "loader/scene_loader.h"
#include "render/render_output.h"
#include "render/renderer.h"
#include "renderer_version.h"

namespace rr {

namespace fs = std::filesystem;

namespace {

std::string readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ConfigError("", "cannot open scene file " + file.string());
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

// Command-line flags become JSON-pointer assignments applied after any --set, so the scene
// document records exactly what was rendered.
void applyCommandLine(Json& doc, const RenderCommandOptions& o) {
    for (const std::string& assignment : o.overrides)
        applyOverride(doc, assignment);
    if (!doc.is_object()) return;  // loadScene reports it
    auto ensureObject = [&](const std::string& key) {
        if (!doc.contains(key)) doc[key] = Json::object();
        if (!doc[key].is_object()) throw ConfigError("/" + key, "expected an object");
    };
    if (o.integrator) {
        ensureObject("integrator");
        doc["integrator"]["type"] = *o.integrator;
    }
    if (o.spp || o.seed || o.resolution) ensureObject("render");
    if (o.spp) doc["render"]["spp"] = *o.spp;
    if (o.seed) doc["render"]["seed"] = *o.seed;
    if (o.resolution) {
        unsigned w = 0, h = 0;
        char extra;
        if (std::sscanf(o.resolution->c_str(), "%ux%u%c", &w, &h, &extra) != 2)
            throw ConfigError("/render/resolution",
                              "--resolution expects WxH, got \"" + *o.resolution + "\"");
        doc["render"]["resolution"] = {w, h};
    }
}

fs::path outputPath(const RenderCommandOptions& o) {
    const fs::path out = o.out ? fs::path(*o.out)
                               : fs::path("results") / (fs::path(o.scene).stem().string() + ".exr");
    if (out.extension() != ".exr")
        throw ConfigError("", "--out must name an .exr file, got \"" + out.string() + "\"");
    return out;
}

std::string featureList(const SceneFeatures& f) {
    std::string s;
    auto add = [&](bool on, const char* name) {
        if (!on) return;
        if (!s.empty()) s += ',';
        s += name;
    };
    add(f.motionBlur, "motion_blur");
    add(f.thinLens, "thin_lens");
    add(f.media, "media");
    return s.empty() ? "none" : s;
}

}  // namespace

int runRenderCommand(const RenderCommandOptions& o) {
    // 1. Everything that can be wrong with the input is checked before anything is written.
    LoadedScene loaded;
    Json document;
    std::string fileText;
    fs::path out;
    try {
        if (!fs::is_regular_file(o.scene))
            throw ConfigError("", "scene file not found: " + o.scene);
        fileText = readFile(o.scene);
        document = parseSceneText(fileText, o.scene);
        applyCommandLine(document, o);
        out = outputPath(o);
        loaded = loadScene(document, AssetResolver::standard(fs::path(o.scene).parent_path()));
    } catch (const ConfigError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    }

    // 2. Render.
    const RenderSettings& settings = loaded.render;
    RenderOptions options;
    options.spp = o.timeLimit > 0 ? (o.spp ? *o.spp : 0) : settings.spp;
    options.timeLimit = o.timeLimit;
    options.seed = settings.seed;
    options.threads = o.threads;
    options.sampler = settings.sampler;
    options.samplerSetSize = settings.spp;
    options.cancel = &installInterruptHandler();
    const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();

    Film film(settings.width, settings.height);
    ProgressBar bar;
    const RenderStats stats = render(*loaded.scene, *loaded.integrator, options, film,
                                     [&](const RenderProgress& p) { bar.update(p); });

    // 3. Write the EXR (with provenance) and the preview, each atomically.
    ExrImage image = filmToExr(film);
    auto& a = image.attributes;
    a["renderer.version"] = std::string(kRendererVersion);
    a["renderer.scene"] = o.scene;
    a["renderer.sceneFileSha256"] = sha256Hex(fileText);
    a["renderer.sceneSha256"] = sha256Hex(document.dump());  // after overrides
    a["renderer.overrides"] = Json(o.overrides).dump();
    a["renderer.integrator"] = loaded.integrator->name();
    a["renderer.integratorParameters"] = loaded.integrator->parameters().dump();
    a["renderer.spp"] = static_cast<int>(stats.spp);
    a["renderer.sppRequested"] = static_cast<int>(options.spp);
    a["renderer.timeLimit"] = o.timeLimit;
    a["renderer.seed"] = static_cast<double>(settings.seed);
    a["renderer.sampler"] = std::string(samplerName(settings.sampler));
    a["renderer.threads"] = threads;
    a["renderer.renderTime"] = stats.seconds;
    a["renderer.features"] = featureList(loaded.scene->features());
    a["renderer.rays.camera"] = static_cast<double>(stats.rays.camera);
    a["renderer.rays.extension"] = static_cast<double>(stats.rays.extension);
    a["renderer.rays.shadow"] = static_cast<double>(stats.rays.shadow);
    a["renderer.nonFiniteSamples"] = static_cast<double>(stats.nonFiniteSamples);
    a["renderer.interrupted"] = stats.interrupted ? 1 : 0;
    a["renderer.channels"] = std::string(
        "R,G,B: mean radiance; variance.R,variance.G,variance.B: variance of the pixel mean; "
        "samples: samples in the pixel");
    try {
        if (out.has_parent_path()) fs::create_directories(out.parent_path());
        writeExr(out, image);
        if (o.preview) {
            fs::path png = out;
            png.replace_extension(".png");
            writePngPreview(png, image.width, image.height, image.channels["R"],
                            image.channels["G"], image.channels["B"], o.exposure);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }

    char summary[512];
    std::snprintf(
        summary, sizeof summary,
        "%s: %s, %dx%d, %u spp in %.2f s (%.2f Mrays/s, %.3f Msamples/s, %d threads)%s -> %s",
        o.scene.c_str(), loaded.integrator->name().c_str(), settings.width, settings.height,
        stats.spp, stats.seconds, stats.rays.total() / stats.seconds * 1e-6,
        double(stats.spp) * settings.width * settings.height / stats.seconds * 1e-6, threads,
        stats.interrupted ? " [interrupted]" : "", out.c_str());
    bar.finish(summary);
    if (stats.nonFiniteSamples > 0)
        std::fprintf(stderr, "warning: %llu non-finite samples were dropped\n",
                     static_cast<unsigned long long>(stats.nonFiniteSamples));
    return stats.interrupted ? 130 : 0;
}

}  // namespace rr
