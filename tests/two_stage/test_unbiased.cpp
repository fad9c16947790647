// Two-stage sampling is unbiased (Cline et al. 2006 §3: the warp tracks the density exactly, and
// the partition's floor keeps it non-zero wherever Le·f is): on each figure scene at 32 × 32,
// the mean of two-stage renders over independent seeds agrees with a long render of the same
// light by direct MIS, for the image mean and every 8 × 8 block mean of every channel, by
// z-tests with a Šidák-corrected family-wise level of 1 %. Fig. 8's three materials, peaks from
// BSDF samples (fig. 9), shadows and two-stage at every vertex of path_mis (fig. 10's scene),
// and a synthetic map that needs no asset; a sphere 2.5 % darker must be rejected (the tests'
// power).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "support/chi2.h"
#include "support/maps.h"
#include "support/mean_agreement.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

constexpr int kSize = 32, kBlock = 8;

struct Case {
    const char* name;
    const char* scene;
    const char* integrator;
    const char* reference;
    uint32_t spp, referenceSpp;
    bool synthetic;  // the scene's light replaced by a synthetic lat-long map
};

constexpr const char* kDirectMis =
    R"({"type":"direct","strategy":"mis","light_samples":1,"bsdf_samples":1})";
constexpr const char* kTwoStage4 =
    R"({"type":"direct","estimator":{"type":"two_stage","samples":4}})";

const Case kCases[] = {
    {"blinn", "twostage_fig8_blinn.json", kTwoStage4, kDirectMis, 16, 4096, false},
    {"ashikhmin", "twostage_fig8_ashikhmin.json", kTwoStage4, kDirectMis, 16, 4096, false},
    {"lafortune", "twostage_fig8_lafortune.json", kTwoStage4, kDirectMis, 16, 4096, false},
    {"lafortune_bsdf_peaks", "twostage_fig8_lafortune.json",
     R"({"type":"direct","estimator":{"type":"two_stage","samples":8,"peaks":"bsdf"}})", kDirectMis,
     8, 4096, false},
    {"penumbrae_path_mis", "twostage_fig10_penumbrae.json",
     R"({"type":"path_mis","estimator":{"type":"two_stage","samples":2}})",
     R"({"type":"path_mis"})", 32, 4096, false},
    {"synthetic_map_blinn", "twostage_fig8_blinn.json", kTwoStage4, kDirectMis, 16, 4096, true},
};
constexpr int kCaseCount = sizeof(kCases) / sizeof(kCases[0]);
constexpr uint32_t kSeeds = 4;

double threshold() {
    // The cases and the negative control.
    return zThreshold(sidakAlpha(0.01, (kCaseCount + 1) * regionTests(kSize, kSize, kBlock)));
}

// A 64 × 32 lat-long map with a bright patch, a black band and a dim lower half.
std::string syntheticMapFile() {
    return writeRgbExr(scratchDirectory("synthetic") / "map.exr", 64, 32,
                       [](int col, int row) {
                           float v = row < 14 ? 0.5f + 0.02f * float(col % 16)
                                              : (row < 17 ? 0.0f : 0.05f);
                           if (col >= 30 && col < 33 && row >= 8 && row < 10) v = 300;
                           return Rgb(v, 0.8f * v, 0.6f * v);
                       })
        .string();
}

bool galileoAvailable() {
    return AssetResolver::standard(TEST_SCENES_DIR)
        .resolve("envmaps/galileo_probe.hdr")
        .has_value();
}

LoadedScene scene(const Case& c, const std::string& integrator) {
    std::vector<std::string> overrides = {"/render/resolution=[32,32]",
                                          "/integrator=" + integrator};
    if (c.synthetic)
        overrides.push_back(R"(/lights/0={"type":"environment","layout":"latlong","file":")" +
                            syntheticMapFile() + "\"}");
    return loadSceneFile(c.scene, overrides);
}

void skipWithoutGalileo(const Case& c) {
    if (c.synthetic || galileoAvailable()) return;
    const char* required = std::getenv("REQUIRE_ASSETS");
    if (required && std::string(required) == "1")
        FAIL() << "REQUIRE_ASSETS=1 but envmaps/galileo_probe.hdr is not on the search path";
    GTEST_SKIP() << "envmaps/galileo_probe.hdr is not on the asset search path";
}

class TwoStageUnbiased : public ::testing::TestWithParam<Case> {};

TEST_P(TwoStageUnbiased, MeanOverSeedsMatchesALongRenderOfTheSameLight) {
    const Case& c = GetParam();
    skipWithoutGalileo(c);
    if (::testing::Test::IsSkipped() || ::testing::Test::HasFailure()) return;
    const TestRender reference = renderScene(scene(c, c.reference), c.referenceSpp, 1000);
    const LoadedScene twoStage = scene(c, c.integrator);
    std::vector<TestRender> renders;
    for (uint32_t seed = 1; seed <= kSeeds; ++seed)
        renders.push_back(renderScene(twoStage, c.spp, seed));
    const Disagreement w = largestDisagreement(renders, reference.film, kBlock, "two-stage");
    std::printf("largest |z| %.2f (threshold %.2f) at %s\n", w.z, threshold(), w.where.c_str());
    EXPECT_LT(w.z, threshold()) << c.scene << " with " << c.integrator << ": " << w.where;
}

INSTANTIATE_TEST_SUITE_P(Scenes, TwoStageUnbiased, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& param) {
                             return std::string(param.param.name);
                         });

// The power of the z-tests above: the synthetic map's Blinn sphere with 2.5 % less reflectance
// must be rejected at the same sample counts.
TEST(TwoStageUnbiasedNegativeControl, ASphere2Point5PercentDarkerIsRejected) {
    const Case& c = kCases[kCaseCount - 1];
    const TestRender reference = renderScene(scene(c, c.reference), c.referenceSpp, 1000);
    std::vector<std::string> overrides = {
        "/render/resolution=[32,32]", "/integrator=" + std::string(c.integrator),
        "/materials/sphere/reflectance=0.975",
        R"(/lights/0={"type":"environment","layout":"latlong","file":")" + syntheticMapFile() +
            "\"}"};
    const LoadedScene darker = loadSceneFile(c.scene, overrides);
    std::vector<TestRender> renders;
    for (uint32_t seed = 1; seed <= kSeeds; ++seed)
        renders.push_back(renderScene(darker, c.spp, seed));
    const Disagreement w = largestDisagreement(renders, reference.film, kBlock, "two-stage");
    std::printf("largest |z| %.2f (threshold %.2f) at %s\n", w.z, threshold(), w.where.c_str());
    EXPECT_GT(w.z, threshold()) << w.where;
}

}  // namespace
}  // namespace rr::test
