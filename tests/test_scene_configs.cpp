// Every scene file in configs/scenes/ loads and renders in-process with path_mis: a 16×16
// image at 1 spp is finite and non-negative in every pixel, and a 32×32 image at 4 spp is not
// black (a black scene is a broken scene: a light that points away, a camera inside a wall).
// Paper scenes must also be named by the convention and carry a description. The files are
// listed at run time, so a new scene is tested without editing this file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "support/scene_testing.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sceneFileNames() {
    std::vector<std::string> names;
    for (const fs::directory_entry& entry : fs::directory_iterator(TEST_SCENES_DIR))
        if (entry.is_regular_file() && entry.path().extension() == ".json")
            names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Every asset a scene names: the string values of "file" keys (meshes, environment maps,
// image textures), wherever they sit in the document.
void collectAssetFiles(const Json& j, std::vector<std::string>& files) {
    if (j.is_object()) {
        for (const auto& [key, value] : j.items()) {
            if (key == "file" && value.is_string()) files.push_back(value.get<std::string>());
            collectAssetFiles(value, files);
        }
    } else if (j.is_array()) {
        for (const Json& element : j)
            collectAssetFiles(element, files);
    }
}

std::optional<std::string> firstMissingAsset(const Json& document) {
    const AssetResolver assets = AssetResolver::standard(TEST_SCENES_DIR);
    std::vector<std::string> files;
    collectAssetFiles(document, files);
    for (const std::string& file : files)
        if (!assets.resolve(file)) return file + " (searched " + assets.describe() + ")";
    return std::nullopt;
}

bool assetsRequired() {
    const char* value = std::getenv("REQUIRE_ASSETS");
    return value != nullptr && std::string(value) == "1";
}

class SceneConfig : public ::testing::TestWithParam<std::string> {
  protected:
    // A scene naming an absent asset is skipped, or fails when REQUIRE_ASSETS=1 (CI must
    // have every asset); either way the test body does not run.
    void SetUp() override {
        document_ = readSceneFile(fs::path(TEST_SCENES_DIR) / GetParam());
        const std::optional<std::string> missing = firstMissingAsset(document_);
        if (!missing) return;
        if (assetsRequired()) FAIL() << "asset " << *missing << " is absent and REQUIRE_ASSETS=1";
        GTEST_SKIP() << "asset " << *missing
                     << " is absent (with REQUIRE_ASSETS=1 this is a failure)";
    }

    // The scene at width × height, rendered with path_mis whatever its own integrator.
    LoadedScene load(int width, int height) const {
        Json document = document_;
        if (!document.contains("render")) document["render"] = Json::object();
        document["render"]["resolution"] = {width, height};
        document["integrator"] = {{"type", "path_mis"}};
        return loadSceneJson(document);
    }

  private:
    Json document_;
};

TEST_P(SceneConfig, RendersFiniteNonNegativePixels) {
    const TestRender r = renderScene(load(16, 16), /*spp=*/1);
    EXPECT_EQ(r.stats.nonFiniteSamples, 0u) << "samples were NaN or infinite";
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                const float v = r.film.mean(x, y)[c];
                ASSERT_TRUE(std::isfinite(v) && v >= 0)
                    << "pixel (" << x << ", " << y << ") channel " << c << " = " << v;
            }
}

TEST_P(SceneConfig, IsNotBlack) {
    const TestRender r = renderScene(load(32, 32), /*spp=*/4);
    double brightest = 0;
    for (int c = 0; c < 3; ++c)
        brightest = std::max(brightest, imageMean(r.film, c).mean);
    EXPECT_GT(brightest, 0) << "every pixel is black";
}

// Paper scenes follow configs/README.md's naming, <paper>_<figure>_<what>.json, and document
// in `description` how they recreate the figure (the papers give no scene files).
class SceneFile : public ::testing::TestWithParam<std::string> {};

TEST_P(SceneFile, PaperScenesAreNamedAndDescribed) {
    static const std::regex paperPrefix("(tais|pmc|ris|twostage)_.*");
    static const std::regex paperName("(tais|pmc|ris|twostage)_(fig|tab)[0-9]+_[a-z0-9_]+\\.json");
    const std::string& name = GetParam();
    if (!std::regex_match(name, paperPrefix)) return;  // not a paper scene
    EXPECT_TRUE(std::regex_match(name, paperName))
        << name << " is not <paper>_<fig|tab><number>_<what>.json";
    const Json document = readSceneFile(fs::path(TEST_SCENES_DIR) / name);
    const auto description = document.find("description");
    ASSERT_NE(description, document.end()) << name << " has no description";
    EXPECT_FALSE(description->get<std::string>().empty()) << name << " has an empty description";
}

// Test names from file names: gtest allows only letters, digits and '_'.
std::string testName(const ::testing::TestParamInfo<std::string>& info) {
    std::string name = fs::path(info.param).stem().string();
    std::replace_if(
        name.begin(), name.end(), [](char ch) { return !std::isalnum(ch); }, '_');
    return name;
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneConfig, ::testing::ValuesIn(sceneFileNames()), testName);
INSTANTIATE_TEST_SUITE_P(Scenes, SceneFile, ::testing::ValuesIn(sceneFileNames()), testName);

}  // namespace
}  // namespace rr::test
