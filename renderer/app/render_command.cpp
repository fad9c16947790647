#include "app/render_command.h"

#include <pthread.h>
#include <sys/resource.h>
#include <tbb/info.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>

#include "app/interrupt.h"
#include "app/progress_bar.h"
#include "config/json_document.h"
#include "io/exr_io.h"
#include "io/png_preview.h"
#include "io/sha256.h"
#include "loader/scene_loader.h"
#include "render/render_output.h"
#include "render/renderer.h"
#include "renderer_version.h"
#include "scene/scene_features.h"

namespace rr {

namespace fs = std::filesystem;

namespace {

void printToStderr(const std::string& line) {
    std::fprintf(stderr, "%s\n", line.c_str());
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
    add(f.bifurcation, "bifurcation");
    add(f.media, "media");
    return s.empty() ? "none" : s;
}

// Everything checked before rendering: a failure here writes nothing.
struct PreparedRender {
    LoadedScene loaded;
    Json document;  // after overrides
    std::string fileText;
    fs::path out;
    uint32_t spp = 0;  // samples per pixel; with a time limit, an upper bound
    std::unique_ptr<RenderSchedule> schedule;
};

// Creates the output directory and proves a file can be written there, so a render is never
// thrown away for want of a writable destination.
void checkOutputWritable(const fs::path& out) {
    std::error_code ec;
    if (fs::is_directory(out, ec))
        throw ConfigError("", "--out names a directory: " + out.string());
    const fs::path dir = out.has_parent_path() ? out.parent_path() : fs::path(".");
    fs::create_directories(dir, ec);
    std::string probeName = out.stem().string();
    probeName.insert(0, 1, '.').append(".probe").append(std::to_string(::getpid()));
    const fs::path probe = dir / probeName;
    const bool writable = std::ofstream(probe).good();
    fs::remove(probe, ec);
    if (!writable) throw ConfigError("", "--out: cannot write in " + dir.string());
}

PreparedRender prepare(const RenderCommandOptions& o, SceneCache* scenes) {
    PreparedRender p;
    if (!fs::is_regular_file(o.scene)) throw ConfigError("", "scene file not found: " + o.scene);
    p.fileText = readSceneText(o.scene);
    p.document = parseSceneText(p.fileText, o.scene);
    applyCommandLine(p.document, o);
    p.out = outputPath(o);
    p.loaded =
        loadScene(p.document, AssetResolver::standard(fs::path(o.scene).parent_path()), scenes);
    const RenderSettings& settings = p.loaded.render;
    p.spp = o.timeLimit > 0 ? (o.spp ? *o.spp : kMaxSpp) : settings.spp;
    p.schedule = p.loaded.schedule(p.loaded.scheduleInputs(p.spp, o.timeLimit));
    if (o.timeLimit > 0 && !p.schedule->supportsTimeLimit())
        throw ConfigError("/integrator/type",
                          p.loaded.integrator->name() +
                              " renders a fixed number of samples per pixel in its own order; "
                              "--time-limit cannot stop it part-way (use --spp)");
    if (!o.checkOnly) checkOutputWritable(p.out);
    return p;
}

// The process's peak resident memory so far (scene, acceleration structure, film and the
// integrator's working memory such as TAIS's maps), in MiB; under `renderer serve`, which
// resets it before each render, the peak during this render with the scenes it keeps. VmHWM,
// not getrusage's ru_maxrss: the kernel carries ru_maxrss across exec, so it would include the
// memory of the (Python) process that forked the renderer.
double peakResidentMiB() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;
}

void addMetadata(const RenderCommandOptions& o, const PreparedRender& p, const RenderStats& stats,
                 int threads, ExrImage* image) {
    const RenderSettings& settings = p.loaded.render;
    auto& a = image->attributes;
    a["renderer.version"] = std::string(kRendererVersion);
    a["renderer.scene"] = o.scene;
    a["renderer.sceneFileSha256"] = sha256Hex(p.fileText);
    a["renderer.sceneSha256"] = sha256Hex(p.document.dump());  // after overrides
    a["renderer.overrides"] = Json(o.overrides).dump();
    a["renderer.integrator"] = p.loaded.integrator->name();
    a["renderer.integratorParameters"] = p.loaded.integrator->parameters().dump();
    a["renderer.spp"] = static_cast<int>(stats.spp);
    a["renderer.sppRequested"] = static_cast<int>(p.spp);
    a["renderer.timeLimit"] = o.timeLimit;
    a["renderer.seed"] = static_cast<double>(settings.seed);
    a["renderer.sampler"] = std::string(samplerName(settings.sampler));
    a["renderer.filter"] = ReconstructionFilter(settings.filter).parameters().dump();
    a["renderer.threads"] = threads;
    a["renderer.renderTime"] = stats.seconds;
    a["renderer.prepareTime"] = p.loaded.prepareSeconds;
    a["renderer.peakMemoryMiB"] = peakResidentMiB();
    a["renderer.features"] = featureList(sceneFeatures(*p.loaded.scene));
    a["renderer.rays.camera"] = static_cast<double>(stats.rays.camera);
    a["renderer.rays.extension"] = static_cast<double>(stats.rays.extension);
    a["renderer.rays.shadow"] = static_cast<double>(stats.rays.shadow);
    a["renderer.nonFiniteSamples"] = static_cast<double>(stats.nonFiniteSamples);
    a["renderer.interrupted"] = stats.interrupted ? 1 : 0;
    std::string channels =
        "R,G,B: pixel estimate of radiance; variance.R,variance.G,variance.B: variance of that "
        "estimate (box filter: of the mean of the pixel's samples; another filter: the "
        "linearised variance of the ratio sum(w L) / sum(w) over the samples splatted to it); "
        "samples: the pixel's own samples";
    for (AuxiliaryChannel& channel : p.loaded.integrator->auxiliaryChannels()) {
        channels += "; " + channel.name + ": " + channel.description;
        image->channels[channel.name] = std::move(channel.values);
    }
    a["renderer.channels"] = channels;
}

// Writes the EXR and the preview with SIGINT held back on this thread (a first Ctrl-C only
// sets the interrupt flag wherever it lands; a second one aborts, leaving at most a temporary
// file, never a half-written output). The preview is encoded on its own thread while the EXR
// is compressed, and written only after the EXR.
void writeOutputs(const RenderCommandOptions& o, const fs::path& out, const ExrImage& image,
                  int threads) {
    sigset_t interrupt, previous;
    sigemptyset(&interrupt);
    sigaddset(&interrupt, SIGINT);
    pthread_sigmask(SIG_BLOCK, &interrupt, &previous);
    try {
        std::future<std::vector<uint8_t>> preview;
        if (o.preview)
            preview = std::async(std::launch::async, [&] {
                return encodePngPreview(image.width, image.height, image.channels.at("R"),
                                        image.channels.at("G"), image.channels.at("B"), o.exposure);
            });
        writeExr(out, image, threads);
        if (preview.valid()) {
            fs::path png = out;
            png.replace_extension(".png");
            writePngPreview(png, preview.get());
        }
    } catch (...) {
        pthread_sigmask(SIG_SETMASK, &previous, nullptr);
        throw;
    }
    pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

// Bad input: one line on stderr, or with `check --json` one object on stdout. Exit status 2.
int reportBadInput(const RenderCommandOptions& o, const Reporter& report,
                   const std::string& message, const std::string& pointer, ConfigError::Kind kind) {
    if (o.checkOnly && o.json) {
        const Json result = {
            {"valid", false},
            {"error", kind == ConfigError::Kind::MissingAsset ? "missing_asset" : "invalid"},
            {"pointer", pointer},
            {"message", message}};
        std::printf("%s\n", result.dump().c_str());
    } else {
        report("error: " + message);
    }
    return 2;
}

// The point and spot lights of the scene that the integrator can neither sample nor hit (it
// finds emitters only by hitting them): its image lacks their light.
int unreachableLights(const PreparedRender& p) {
    if (p.loaded.integrator->samplesLights()) return 0;
    const auto lights = p.loaded.scene->lights();
    return int(std::count_if(lights.begin(), lights.end(),
                             [](const Light* light) { return light->isDelta(); }));
}

// `renderer check`: the scene is valid. The document hash is what a render records as
// renderer.sceneSha256: it identifies the scene after overrides, independent of the file's
// whitespace and comments. The estimand hash leaves out what changes only the estimator
// (estimandOf): the harness's reference key.
int reportValid(const RenderCommandOptions& o, const PreparedRender& p) {
    const RenderSettings& settings = p.loaded.render;
    const std::string features = featureList(sceneFeatures(*p.loaded.scene));
    const std::string sceneSha = sha256Hex(p.document.dump());
    const std::string estimandSha = sha256Hex(estimandOf(p.document).dump());
    if (o.json) {
        const Json result = {{"valid", true},
                             {"integrator", p.loaded.integrator->name()},
                             {"resolution", {settings.width, settings.height}},
                             {"spp", settings.spp},
                             {"features", features},
                             {"sceneSha256", sceneSha},
                             {"estimandSha256", estimandSha},
                             {"pinned", p.loaded.integrator->pinnedSettings()},
                             {"transport", transportName(p.loaded.integrator->transport())},
                             {"timeLimit", p.schedule->supportsTimeLimit()},
                             {"unreachableLights", unreachableLights(p)}};
        std::printf("%s\n", result.dump().c_str());
    } else {
        std::printf(
            "%s: valid (%s, %dx%d, %u spp, features: %s)\nscene sha256 %s\n"
            "estimand sha256 %s\n",
            o.scene.c_str(), p.loaded.integrator->name().c_str(), settings.width, settings.height,
            settings.spp, features.c_str(), sceneSha.c_str(), estimandSha.c_str());
    }
    return 0;
}

// The one-line summary of a finished render.
std::string summaryLine(const RenderCommandOptions& o, const PreparedRender& p,
                        const RenderStats& stats, int threads, double writeSeconds) {
    const RenderSettings& settings = p.loaded.render;
    char summary[512];
    std::snprintf(
        summary, sizeof summary,
        "%s: %s, %dx%d, %u spp in %.2f s (%.2f Mrays/s, %.3f Msamples/s, %d threads)%s -> %s "
        "(written in %.0f ms)",
        o.scene.c_str(), p.loaded.integrator->name().c_str(), settings.width, settings.height,
        stats.spp, stats.seconds, stats.rays.total() / stats.seconds * 1e-6,
        double(stats.spp) * settings.width * settings.height / stats.seconds * 1e-6, threads,
        stats.interrupted ? " [interrupted]" : "", p.out.c_str(), writeSeconds * 1e3);
    return summary;
}

}  // namespace

int runRenderCommand(const RenderCommandOptions& o, const RenderEnvironment& environment) {
    const Reporter report = environment.report ? environment.report : printToStderr;
    PreparedRender p;
    try {
        p = prepare(o, environment.scenes);
    } catch (const ConfigError& e) {
        return reportBadInput(o, report, e.what(), e.pointer(), e.kind());
    } catch (const fs::filesystem_error& e) {  // unreadable scene or asset: bad input too
        return reportBadInput(o, report, e.what(), "", ConfigError::Kind::Invalid);
    } catch (const std::exception& e) {
        report(std::string("error: ") + e.what());
        return 1;
    }

    const RenderSettings& settings = p.loaded.render;
    if (o.checkOnly) return reportValid(o, p);
    RenderOptions options;
    options.timeLimit = o.timeLimit;
    options.seed = settings.seed;
    options.threads = o.threads;
    options.sampler = settings.sampler;
    options.samplerSetSize = settings.spp;
    options.cancel = &installInterruptHandler();
    const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();

    ProgressBar bar(environment.progressBar);
    RenderStats stats;
    double writeSeconds = 0;
    try {
        Film film(settings.width, settings.height, p.loaded.filmFilter());
        stats = render(*p.schedule, options, film,
                       [&](const RenderProgress& progress) { bar.update(progress); });
        if (!stats.complete) {  // interrupted before any image was complete
            bar.clear();
            report("interrupted before a complete image; nothing written");
            return 130;
        }
        ExrImage image = filmToExr(film, p.loaded.integrator->pixelEstimates());
        addMetadata(o, p, stats, threads, &image);
        const auto writeStart = std::chrono::steady_clock::now();
        writeOutputs(o, p.out, image, threads);
        writeSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - writeStart).count();
    } catch (const std::exception& e) {
        bar.clear();
        report(std::string("error: ") + e.what());
        return 1;
    }

    bar.clear();
    report(summaryLine(o, p, stats, threads, writeSeconds));
    if (stats.nonFiniteSamples > 0)
        report("warning: " + std::to_string(stats.nonFiniteSamples) +
               " non-finite samples were replaced by zero");
    return stats.interrupted ? 130 : 0;
}

}  // namespace rr
