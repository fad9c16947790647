#include "fuzz_support.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <variant>

#include "app/render_command.h"
#include "io/exr_io.h"

namespace rr::fuzz {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void finding(const std::string& what) {
    std::fprintf(stderr, "fuzz finding: %s\n", what.c_str());
    std::abort();
}

// A rendered image must have every sample finite (the loop replaces a non-finite one by zero and
// counts it) and every pixel finite and non-negative.
void checkImage(const fs::path& file) {
    const ExrImage image = readExr(file);
    const auto count = image.attributes.find("renderer.nonFiniteSamples");
    if (count == image.attributes.end())
        finding("no renderer.nonFiniteSamples in " + file.string());
    if (const double* n = std::get_if<double>(&count->second); !n || *n != 0)
        finding("non-finite samples were rendered");
    for (const char* channel : {"R", "G", "B"})
        for (float v : image.channels.at(channel))
            if (!std::isfinite(v) || v < 0)
                finding(std::string("pixel ") + channel + " = " + std::to_string(v));
}

void removeScratchDirectory() {
    std::error_code ignored;
    fs::remove_all(scratchDirectory(), ignored);
}

}  // namespace

const fs::path& scratchDirectory() {
    static const fs::path dir = [] {
        const fs::path base =
            fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
        fs::path d = base / ("rr_fuzz_" + std::to_string(::getpid()));
        fs::create_directories(d);
        std::atexit(removeScratchDirectory);
        return d;
    }();
    return dir;
}

fs::path writeInput(std::string_view name, const uint8_t* data, size_t size) {
    const fs::path file = scratchDirectory() / name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) finding("cannot write " + file.string());
    return file;
}

fs::path writeFixedFile(std::string_view name, std::string_view text) {
    const fs::path file = scratchDirectory() / name;
    if (!fs::exists(file))
        writeInput(name, reinterpret_cast<const uint8_t*>(text.data()), text.size());
    return file;
}

void renderOnePixel(const fs::path& scene) {
    const fs::path out = scratchDirectory() / "out.exr";
    std::error_code ignored;
    fs::remove(out, ignored);
    RenderCommandOptions options;
    options.scene = scene.string();
    options.resolution = "1x1";
    options.spp = 1;
    options.threads = 1;
    options.out = out.string();
    options.preview = false;
    RenderEnvironment environment;
    environment.report = [](const std::string&) {};
    environment.progressBar = false;
    switch (const int status = runRenderCommand(options, environment)) {
        case 0:
            checkImage(out);
            break;
        case 2:
            if (fs::exists(out)) finding("a rejected input wrote " + out.string());
            break;
        case 130:
            // A Ctrl-C: the render command took SIGINT from libFuzzer and keeps its flag, so
            // every later input would be interrupted too. Stop, as libFuzzer would.
            std::fprintf(stderr, "interrupted\n");
            std::exit(130);
        default:
            finding("exit status " + std::to_string(status));
    }
}

}  // namespace rr::fuzz
