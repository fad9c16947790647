// The renderer binary end to end: outputs and metadata, exit status 2 with one message for bad
// input and nothing written, time-limited renders, Ctrl-C, and thread-count independence.
#include <gtest/gtest.h>
#include <signal.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "io/exr_io.h"
#include "support/child_process.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

const std::string kScene = std::string(TEST_SCENES_DIR) + "/cornell_spheres.json";

ChildProcess start(const std::vector<std::string>& args, const fs::path& dir) {
    return startProcess(RENDERER_BINARY, args, dir);
}

int wait(const ChildProcess& p, std::string* errors = nullptr) {
    const ProcessResult r = waitProcess(p);
    if (errors) *errors = r.errors;
    return r.status;
}

int run(const std::vector<std::string>& args, const fs::path& dir, std::string* errors = nullptr) {
    return wait(start(args, dir), errors);
}

std::string attribute(const ExrImage& image, const std::string& name) {
    const auto& v = image.attributes.at(name);
    if (const auto* s = std::get_if<std::string>(&v)) return *s;
    if (const auto* i = std::get_if<int>(&v)) return std::to_string(*i);
    std::ostringstream o;
    o << std::get<double>(v);
    return o.str();
}

// The preview is the image's sRGB encoding at exposure 0, 8 bits per channel.
void expectPreviewOf(const ExrImage& image, const fs::path& png) {
    int width = 0, height = 0, components = 0;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load(png.c_str(), &width, &height, &components, 3), stbi_image_free);
    ASSERT_TRUE(pixels) << png << ": " << stbi_failure_reason();
    ASSERT_EQ(width, image.width);
    ASSERT_EQ(height, image.height);
    EXPECT_EQ(components, 3);
    const char* names[] = {"R", "G", "B"};
    for (size_t i = 0; i < size_t(width) * height; ++i)
        for (int c = 0; c < 3; ++c) {
            const float linear = std::clamp(image.channels.at(names[c])[i], 0.0f, 1.0f);
            const float srgb = linear <= 0.0031308f
                                   ? 12.92f * linear
                                   : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
            ASSERT_EQ(pixels.get()[3 * i + c], std::lround(srgb * 255.0f)) << i << names[c];
        }
}

TEST(Cli, RenderWritesExrWithChannelsAndMetadataAndPngPreview) {
    const fs::path dir = scratchDirectory();
    std::string errors;
    ASSERT_EQ(run({"render", kScene, "--resolution", "24x16", "--spp", "4", "--seed", "3", "--set",
                   "/render/max_depth=5", "--out", (dir / "out.exr").string()},
                  dir, &errors),
              0)
        << errors;
    const ExrImage image = readExr(dir / "out.exr");
    expectPreviewOf(image, dir / "out.png");
    EXPECT_EQ(image.width, 24);
    EXPECT_EQ(image.height, 16);
    for (const char* c : {"R", "G", "B", "variance.R", "variance.G", "variance.B", "samples"})
        EXPECT_TRUE(image.channels.count(c)) << c;
    EXPECT_EQ(image.channels.at("samples")[0], 4.0f);
    EXPECT_EQ(attribute(image, "renderer.spp"), "4");
    EXPECT_EQ(attribute(image, "renderer.seed"), "3");
    EXPECT_EQ(attribute(image, "renderer.integrator"), "path_mis");
    EXPECT_NE(attribute(image, "renderer.integratorParameters").find("\"max_depth\":5"),
              std::string::npos);
    EXPECT_NE(attribute(image, "renderer.overrides").find("/render/max_depth=5"),
              std::string::npos);
    EXPECT_EQ(attribute(image, "renderer.sceneFileSha256").size(), 64u);
    // The default scene is static, pinhole and without media; its glass sphere bifurcates.
    EXPECT_EQ(attribute(image, "renderer.features"), "bifurcation");
    for (const char* key : {"renderer.version", "renderer.scene", "renderer.sceneSha256",
                            "renderer.threads", "renderer.renderTime", "renderer.sampler"})
        EXPECT_TRUE(image.attributes.count(key)) << key;
    // Non-interactive stderr: exactly one summary line.
    EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

struct BadRun {
    const char* what;
    std::vector<std::string> args;
    const char* mentions;
};

void PrintTo(const BadRun& b, std::ostream* os) {
    *os << b.what;
}

class CliBadInput : public ::testing::TestWithParam<BadRun> {};

TEST_P(CliBadInput, ExitsWithStatusTwoOneMessageAndWritesNothing) {
    const fs::path dir = scratchDirectory();
    const fs::path malformed = dir / "malformed.json";
    std::ofstream(malformed) << "{ \"camera\": { \"fov\": 40,, } }";
    std::vector<std::string> args;
    for (std::string a : GetParam().args) {
        if (a == "SCENE") a = kScene;
        if (a == "MALFORMED") a = malformed.string();
        args.push_back(a);
    }
    args.insert(args.end(), {"--out", (dir / "out" / "image.exr").string()});
    std::string errors;
    EXPECT_EQ(run(args, dir, &errors), 2) << errors;
    EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
    EXPECT_NE(errors.find(GetParam().mentions), std::string::npos) << errors;
    EXPECT_FALSE(fs::exists(dir / "out")) << "nothing may be written";
}

INSTANTIATE_TEST_SUITE_P(
    All, CliBadInput,
    ::testing::Values(
        BadRun{"malformed JSON", {"render", "MALFORMED"}, "line 1"},
        BadRun{
            "missing scene file", {"render", "/nonexistent/scene.json"}, "/nonexistent/scene.json"},
        BadRun{"negative radius",
               {"render", "SCENE", "--set", "/shapes/8/radius=-1"},
               "/shapes/8/radius"},
        BadRun{"unknown key", {"render", "SCENE", "--set", "/camera/zoom=2"}, "/camera/zoom"},
        BadRun{
            "unknown integrator", {"render", "SCENE", "--integrator", "bdpt"}, "/integrator/type"},
        BadRun{
            "missing mesh",
            {"render", "SCENE", "--set",
             "/shapes/8={\"type\":\"mesh\",\"file\":\"meshes/none.ply\",\"material\":\"white\"}"},
            "/shapes/8/file"},
        BadRun{"bad --set pointer",
               {"render", "SCENE", "--set", "/camera/lens/radius=1"},
               "/camera/lens/radius"},
        BadRun{
            "bad --resolution", {"render", "SCENE", "--resolution", "12by8"}, "/render/resolution"},
        BadRun{"zero spp", {"render", "SCENE", "--spp", "0"}, "--spp"},
        BadRun{"unknown option", {"render", "SCENE", "--sppp", "3"}, "--sppp"}),
    [](const ::testing::TestParamInfo<BadRun>& param) {
        std::string name = param.param.what;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

// An output that cannot be written is found before rendering (status 2), not after.
TEST(Cli, CheckValidatesWithoutWritingAndHashesTheDocumentAfterOverrides) {
    const fs::path dir = scratchDirectory();
    const ProcessResult plain = runProcess(RENDERER_BINARY, {"check", kScene}, dir);
    ASSERT_EQ(plain.status, 0) << plain.errors;
    const size_t at = plain.out.find("scene sha256 ");
    ASSERT_NE(at, std::string::npos) << plain.out;
    const std::string hash = plain.out.substr(at + 13, 64);
    const ProcessResult overridden =
        runProcess(RENDERER_BINARY, {"check", kScene, "--set", "/render/spp=3"}, dir);
    ASSERT_EQ(overridden.status, 0) << overridden.errors;
    EXPECT_EQ(overridden.out.find(hash), std::string::npos) << "an override must change the hash";
    const ProcessResult again = runProcess(RENDERER_BINARY, {"check", kScene}, dir);
    EXPECT_NE(again.out.find(hash), std::string::npos);

    const ProcessResult bad =
        runProcess(RENDERER_BINARY, {"check", kScene, "--set", "/render/sppp=3"}, dir);
    EXPECT_EQ(bad.status, 2);
    EXPECT_NE(bad.errors.find("/render/sppp"), std::string::npos) << bad.errors;
    size_t files = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir))
        ++files;
    EXPECT_EQ(files, 2u) << "only the captured stdout.txt and stderr.txt";
}

// `check --json` tells a missing asset from other bad input by a field, not by wording: the
// experiment harness skips scenes whose third-party files are absent on this machine.
TEST(Cli, CheckJsonSaysValidInvalidOrMissingAsset) {
    const fs::path dir = scratchDirectory();
    const ProcessResult valid = runProcess(RENDERER_BINARY, {"check", kScene, "--json"}, dir);
    ASSERT_EQ(valid.status, 0) << valid.errors;
    const nlohmann::json ok = nlohmann::json::parse(valid.out);
    EXPECT_EQ(ok.at("valid"), true);
    EXPECT_EQ(ok.at("integrator"), "path_mis");
    EXPECT_EQ(ok.at("sceneSha256").get<std::string>().size(), 64u);

    const ProcessResult invalid =
        runProcess(RENDERER_BINARY, {"check", kScene, "--json", "--set", "/render/spp=0"}, dir);
    EXPECT_EQ(invalid.status, 2);
    const nlohmann::json bad = nlohmann::json::parse(invalid.out);
    EXPECT_EQ(bad.at("valid"), false);
    EXPECT_EQ(bad.at("error"), "invalid");
    EXPECT_EQ(bad.at("pointer"), "/render/spp");

    const fs::path scene = dir / "missing_mesh.json";
    std::ofstream(scene) << R"({"camera": {"position": [0, 0, 5], "look_at": [0, 0, 0]},
        "shapes": [{"type": "mesh", "file": "no_such_mesh_anywhere.ply",
                    "material": {"type": "lambert", "albedo": 0.5}}],
        "lights": [{"type": "point", "position": [0, 3, 0], "intensity": 1}]})";
    const ProcessResult missing =
        runProcess(RENDERER_BINARY, {"check", scene.string(), "--json"}, dir);
    EXPECT_EQ(missing.status, 2);
    const nlohmann::json absent = nlohmann::json::parse(missing.out);
    EXPECT_EQ(absent.at("error"), "missing_asset");
    EXPECT_EQ(absent.at("pointer"), "/shapes/0/file");
}

// `check --json` says which keys make a render reproducible (the harness's fingerprints): none
// for an integrator whose choices measure nothing, given costs for RIS's robust M and N.
TEST(Cli, CheckJsonPinsWhatATechniqueMeasures) {
    const fs::path dir = scratchDirectory();
    const ProcessResult plain = runProcess(RENDERER_BINARY, {"check", kScene, "--json"}, dir);
    ASSERT_EQ(plain.status, 0) << plain.errors;
    EXPECT_EQ(nlohmann::json::parse(plain.out).at("pinned"), nlohmann::json::object());

    const std::string robust = R"(/integrator={"type":"ris","mode":"robust","budget":4})";
    const ProcessResult timed =
        runProcess(RENDERER_BINARY, {"check", kScene, "--json", "--set", robust}, dir);
    ASSERT_EQ(timed.status, 0) << timed.errors;
    const nlohmann::json pinned = nlohmann::json::parse(timed.out).at("pinned");
    EXPECT_GT(pinned.at("costs").at("t_x_ns").get<double>(), 0);
    EXPECT_GT(pinned.at("costs").at("t_y_ns").get<double>(), 0);

    const std::string given =
        R"(/integrator={"type":"ris","mode":"robust","budget":4,"costs":{"t_x_ns":40,"t_y_ns":300}})";
    const ProcessResult fixed =
        runProcess(RENDERER_BINARY, {"check", kScene, "--json", "--set", given}, dir);
    ASSERT_EQ(fixed.status, 0) << fixed.errors;
    EXPECT_EQ(nlohmann::json::parse(fixed.out).at("pinned"), nlohmann::json::object());
}

// `check --json` says what image an integrator estimates and how it can be budgeted (the
// cross-paper matrix's columns): its light transport, whether a time limit can stop it, and
// the point and spot lights it cannot reach because it finds emitters only by hitting them.
TEST(Cli, CheckJsonSaysWhatAnIntegratorEstimates) {
    const fs::path dir = scratchDirectory();
    auto check = [&](const std::string& scene, const std::string& integrator) {
        const ProcessResult r = runProcess(
            RENDERER_BINARY, {"check", scene, "--json", "--set", "/integrator=" + integrator}, dir);
        EXPECT_EQ(r.status, 0) << r.errors;
        return nlohmann::json::parse(r.out);
    };
    const nlohmann::json direct = check(kScene, R"({"type":"direct"})");
    EXPECT_EQ(direct.at("transport"), "direct");
    EXPECT_EQ(direct.at("timeLimit"), true);
    EXPECT_EQ(direct.at("unreachableLights"), 0);
    const nlohmann::json wrapped =
        check(kScene, R"({"type":"pmc_ip","integrator":{"type":"path_mis"}})");
    EXPECT_EQ(wrapped.at("transport"), "paths");  // a wrapper's is its pixel integrator's
    EXPECT_EQ(check(kScene, R"({"type":"tais"})").at("timeLimit"), false);

    const std::string spots = std::string(TEST_SCENES_DIR) + "/tais_fig8_spot_lights.json";
    EXPECT_EQ(check(spots, R"({"type":"path_mis"})").at("unreachableLights"), 0);
    EXPECT_EQ(check(spots, R"({"type":"path"})").at("unreachableLights"), 22);
    EXPECT_EQ(
        check(spots, R"({"type":"path_mis","estimator":{"type":"bsdf"}})").at("unreachableLights"),
        22);
    EXPECT_EQ(check(spots, R"({"type":"path_mis","estimator":{"type":"ris","source":"bsdf"}})")
                  .at("unreachableLights"),
              22);
    EXPECT_EQ(
        check(spots, R"({"type":"path_mis","estimator":{"type":"ris"}})").at("unreachableLights"),
        0);
}

TEST(Cli, UnwritableOutputIsRejectedBeforeRendering) {
    const fs::path dir = scratchDirectory();
    fs::create_directories(dir / "taken.exr");
    for (const fs::path& out : {dir / "taken.exr", fs::path("/proc/rr_test/out.exr")}) {
        std::string errors;
        EXPECT_EQ(run({"render", kScene, "--spp", "100000", "--out", out.string()}, dir, &errors),
                  2)
            << out;
        EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
        EXPECT_NE(errors.find("--out"), std::string::npos) << errors;
    }
    EXPECT_TRUE(fs::is_empty(dir / "taken.exr"));
}

TEST(Cli, TimeLimitRecordsTheSamplesReached) {
    const fs::path dir = scratchDirectory();
    std::string errors;
    ASSERT_EQ(run({"render", kScene, "--resolution", "32x32", "--time-limit", "0.5", "--out",
                   (dir / "t.exr").string(), "--no-preview"},
                  dir, &errors),
              0)
        << errors;
    const ExrImage image = readExr(dir / "t.exr");
    const int spp = std::stoi(attribute(image, "renderer.spp"));
    EXPECT_GE(spp, 1);
    for (float s : image.channels.at("samples"))
        ASSERT_EQ(s, float(spp));
    EXPECT_EQ(attribute(image, "renderer.timeLimit"), "0.5");
}

// TAIS scans pixels in order with a fixed spp: a time limit cannot stop it part-way.
TEST(Cli, TaisRefusesATimeLimitAndWritesNothing) {
    const fs::path dir = scratchDirectory();
    std::string errors;
    EXPECT_EQ(run({"render", kScene, "--resolution", "16x16", "--integrator", "tais",
                   "--time-limit", "0.5", "--out", (dir / "t.exr").string()},
                  dir, &errors),
              2);
    EXPECT_NE(errors.find("/integrator/type"), std::string::npos) << errors;
    EXPECT_EQ(std::count(errors.begin(), errors.end(), '\n'), 1) << errors;
    EXPECT_FALSE(fs::exists(dir / "t.exr"));
    EXPECT_FALSE(fs::exists(dir / "t.png"));
}

TEST(Cli, InterruptSavesAValidImageOfTheSamplesReached) {
    const fs::path dir = scratchDirectory();
    const ChildProcess p = start({"render", kScene, "--resolution", "64x64", "--spp", "1000000",
                                  "--out", (dir / "i.exr").string(), "--no-preview"},
                                 dir);
    // Wait until rendering has started (the scene loads in milliseconds), then interrupt.
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    kill(p.pid, SIGINT);
    std::string errors;
    EXPECT_EQ(wait(p, &errors), 130) << errors;
    const ExrImage image = readExr(dir / "i.exr");
    const int spp = std::stoi(attribute(image, "renderer.spp"));
    EXPECT_GE(spp, 1);
    EXPECT_LT(spp, 1000000);
    EXPECT_EQ(attribute(image, "renderer.interrupted"), "1");
    for (float s : image.channels.at("samples"))
        ASSERT_EQ(s, float(spp));
}

// SIGKILL at moments spread over a whole render and its writing (a fixed sequence of delays,
// some landing while the EXR and PNG are written): each output is then either the previous
// render's file or a complete new one of the same pixels; never a partial file.
TEST(Cli, KilledRenderLeavesTheOldOutputOrACompleteNewOne) {
    const fs::path dir = scratchDirectory();
    const fs::path out = dir / "k.exr", png = dir / "k.png";
    const std::vector<std::string> args = {"render", kScene, "--resolution", "256x256",
                                           "--spp",  "1",    "--out",        out.string()};
    const auto began = std::chrono::steady_clock::now();
    ASSERT_EQ(run(args, dir), 0);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    const std::string oldExr = readText(out), oldPng = readText(png);
    const ExrImage reference = readExr(out);
    constexpr int kKills = 12;
    for (int k = 0; k < kKills; ++k) {
        const ChildProcess p = start(args, dir);
        // Delays from 0 to 1.2× a whole run, in a fixed order.
        std::this_thread::sleep_for(std::chrono::duration<double>(seconds * 1.2 * k / kKills));
        kill(p.pid, SIGKILL);
        wait(p);
        const std::string exr = readText(out);
        if (exr != oldExr) {
            // Only a complete render replaces the file: the same pixels (same seed and spp).
            const ExrImage image = readExr(out);
            ASSERT_EQ(image.channels.at("R"), reference.channels.at("R")) << "kill " << k;
        }
        // The preview of the same pixels is the same bytes, old or new.
        ASSERT_EQ(readText(png), oldPng) << "kill " << k;
    }
}

TEST(Cli, ThreadCountDoesNotChangePixels) {
    const fs::path dir = scratchDirectory();
    for (const char* t : {"1", "2"})
        ASSERT_EQ(run({"render", kScene, "--resolution", "40x24", "--spp", "6", "--threads", t,
                       "--out", (dir / (std::string("t") + t + ".exr")).string(), "--no-preview"},
                      dir),
                  0);
    const ExrImage a = readExr(dir / "t1.exr"), b = readExr(dir / "t2.exr");
    for (const auto& [name, data] : a.channels)
        EXPECT_EQ(data, b.channels.at(name)) << name;
}

}  // namespace
}  // namespace rr::test
