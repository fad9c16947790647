// RIS is unbiased (Talbot et al. 2005 §4: for any M, N ≥ 1 when ĝ, p > 0 wherever f ≠ 0): on
// every RIS scene at 32 × 32, the mean of RIS renders over independent seeds agrees with a
// long render of the same light by another estimator, for the image mean and every 8 × 8
// block mean of every channel, by z-tests with a Šidák-corrected family-wise level of 1 %.
// Each source (light, the two hemispheres, the BSDF, the light/BSDF mixture), fractional M and N
// (random rounding), each M/N choice, and RIS at every vertex of path_mis. With M = 1 RIS is light
// sampling, bit for bit; with given costs every mode is bit-identical for any thread count.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "support/chi2.h"
#include "support/mean_agreement.h"

namespace rr::test {
namespace {

constexpr int kSize = 32, kBlock = 8;

LoadedScene scene(const std::string& file, const std::string& integrator,
                  const std::vector<std::string>& changes = {}) {
    std::vector<std::string> overrides = {"/render/resolution=[32,32]",
                                          "/integrator=" + integrator};
    overrides.insert(overrides.end(), changes.begin(), changes.end());
    return loadSceneFile(file, overrides);
}

struct Case {
    const char* name;
    const char* scene;
    const char* integrator;
    const char* reference;
    uint32_t seeds, spp, referenceSpp;
    std::vector<std::string> changes = {};  // further overrides of the scene
};

constexpr const char* kDirectMis = R"({"type":"direct","strategy":"mis"})";
constexpr const char* kPathMis = R"({"type":"path_mis"})";
// Light sampling alone, for scenes with specular lobes: like RIS it leaves out the light they
// reflect, which direct MIS's BSDF samples would find.
constexpr const char* kDirectLight = R"({"type":"direct","strategy":"light","light_samples":4})";

const Case kCases[] = {
    {"dragon_env_light", "ris_fig4_dragon_env.json",
     R"({"type":"ris","mode":"fixed","candidates":3.5,"samples":1.5})", kDirectMis, 4, 64, 2048},
    {"dragon_env_light_proxy", "ris_fig4_dragon_env.json",
     R"({"type":"ris","mode":"fixed","source":"light_proxy","candidates":3.5,"samples":1.5})",
     kDirectMis, 4, 64, 2048},
    {"dragon_no_env_light", "ris_fig4_dragon_no_env.json",
     R"({"type":"ris","mode":"fixed","candidates":3.5,"samples":1.5})", kDirectMis, 4, 64, 2048},
    {"dragon_env_robust", "ris_fig4_dragon_env.json",
     R"({"type":"ris","mode":"robust","budget":4,"costs":{"t_x_ns":40,"t_y_ns":300}})", kDirectMis,
     4, 32, 2048},
    {"dragon_env_optimal", "ris_fig4_dragon_env.json",
     R"({"type":"ris","mode":"optimal","budget":4,"costs":{"t_x_ns":40,"t_y_ns":300}})", kDirectMis,
     4, 32, 2048},
    {"dragon_env_path_mis", "ris_fig4_dragon_env.json",
     R"({"type":"path_mis","estimator":{"type":"ris","candidates":4,"samples":1}})", kPathMis, 4,
     64, 1024},
    {"diffuse_uniform_hemisphere", "ris_fig5_diffuse_sphere.json",
     R"({"type":"ris","mode":"fixed","source":"uniform_hemisphere","candidates":20})", kDirectMis,
     4, 64, 2048},
    {"diffuse_light", "ris_fig5_diffuse_sphere.json",
     R"({"type":"ris","mode":"fixed","candidates":8})", kDirectMis, 4, 64, 2048},
    {"cook_torrance_uniform_hemisphere", "ris_fig5_cook_torrance_sphere.json",
     R"({"type":"ris","mode":"fixed","source":"uniform_hemisphere","candidates":20})", kDirectMis,
     4, 256, 4096},
    {"cook_torrance_cosine_hemisphere", "ris_fig5_cook_torrance_sphere.json",
     R"({"type":"ris","mode":"fixed","source":"cosine_hemisphere","candidates":20})", kDirectMis, 4,
     256, 4096},
    {"cook_torrance_bsdf", "ris_fig5_cook_torrance_sphere.json",
     R"({"type":"ris","mode":"fixed","source":"bsdf","candidates":6.5,"samples":2})", kDirectMis, 4,
     64, 4096},
    {"penumbrae_mixture", "twostage_fig10_penumbrae.json",
     R"({"type":"ris","mode":"fixed","source":"mixture","candidates":2.5,"samples":1.5})",
     kDirectMis, 4, 64, 2048},
    // Two infinite lights (the densities of both in p) and a material whose BSDF draws pick
    // between a mirror, which the mixture drops, and a glossy lobe (the reused lobe coordinate).
    {"penumbrae_mixture_two_lights_mirror_mix",
     "twostage_fig10_penumbrae.json",
     R"({"type":"ris","mode":"fixed","source":"mixture","candidates":3,"samples":1})",
     kDirectLight,
     4,
     64,
     2048,
     {R"(/lights=[{"type":"environment","file":"envmaps/galileo_probe.hdr","layout":"probe","latlong_width":1024},
                   {"type":"environment","radiance":[0.3,0.2,0.1]}])",
      R"(/materials/diffuse={"type":"mix","materials":[{"type":"mirror"},{"type":"blinn","roughness":0.2}],"weight":0.4})"}},
};
constexpr int kCaseCount = sizeof(kCases) / sizeof(kCases[0]);

double threshold() {
    return zThreshold(sidakAlpha(0.01, kCaseCount * regionTests(kSize, kSize, kBlock)));
}

class RisUnbiased : public ::testing::TestWithParam<Case> {};

TEST_P(RisUnbiased, MeanOverSeedsMatchesALongRenderOfTheSameLight) {
    const Case& c = GetParam();
    const TestRender reference =
        renderScene(scene(c.scene, c.reference, c.changes), c.referenceSpp, 1000);
    const LoadedScene ris = scene(c.scene, c.integrator, c.changes);
    std::vector<TestRender> renders;
    for (uint32_t seed = 1; seed <= c.seeds; ++seed)
        renders.push_back(renderScene(ris, c.spp, seed));
    const Disagreement w = largestDisagreement(renders, reference.film, kBlock, "RIS");
    std::printf("largest |z| %.2f (threshold %.2f) at %s\n", w.z, threshold(), w.where.c_str());
    EXPECT_LT(w.z, threshold()) << c.scene << " with " << c.integrator << ": " << w.where;
}

INSTANTIATE_TEST_SUITE_P(Scenes, RisUnbiased, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& param) {
                             return std::string(param.param.name);
                         });

// The test's power: a sphere 2.5 % darker than the reference's (albedo 0.78 for 0.8) must be
// rejected at the same sample counts, or the z-tests above could not see a bias of that size.
TEST(RisUnbiasedNegativeControl, ASphere2Point5PercentDarkerIsRejected) {
    const TestRender reference =
        renderScene(scene("ris_fig5_diffuse_sphere.json", kDirectMis), 2048, 1000);
    const LoadedScene darker = loadSceneFile(
        "ris_fig5_diffuse_sphere.json",
        {"/render/resolution=[32,32]", "/materials/sphere/albedo=0.78",
         R"(/integrator={"type":"ris","mode":"fixed","source":"uniform_hemisphere","candidates":20})"});
    std::vector<TestRender> renders;
    for (uint32_t seed = 1; seed <= 4; ++seed)
        renders.push_back(renderScene(darker, 64, seed));
    const Disagreement w = largestDisagreement(renders, reference.film, kBlock, "RIS");
    std::printf("largest |z| %.2f (threshold %.2f) at %s\n", w.z, threshold(), w.where.c_str());
    EXPECT_GT(w.z, threshold()) << w.where;
}

// Bit-identical images of two integrators' JSON on one scene.
void expectSamePixels(const std::string& file, const std::string& a, const std::string& b,
                      uint32_t spp, int threadsA = 0, int threadsB = 0) {
    const TestRender ra = renderScene(scene(file, a), spp, 3, threadsA);
    const TestRender rb = renderScene(scene(file, b), spp, 3, threadsB);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c) {
                ASSERT_EQ(ra.film.mean(x, y)[c], rb.film.mean(x, y)[c])
                    << a << " vs " << b << " pixel " << x << "," << y;
                ASSERT_EQ(ra.film.varianceOfMean(x, y)[c], rb.film.varianceOfMean(x, y)[c]);
            }
}

TEST(Ris, WithOneCandidateItIsLightSamplingBitForBit) {
    expectSamePixels("ris_fig4_dragon_env.json",
                     R"({"type":"ris","mode":"fixed","candidates":1,"samples":4})",
                     R"({"type":"direct","strategy":"light","light_samples":4})", 4);
    expectSamePixels("ris_fig4_dragon_env.json",
                     R"({"type":"path_mis","estimator":{"type":"ris","candidates":1,"samples":2}})",
                     R"({"type":"path_mis","estimator":{"type":"light","light_samples":2}})", 4);
}

TEST(Ris, GivenCostsMakeEveryModeBitIdenticalForAnyThreadCount) {
    for (const char* integrator :
         {R"({"type":"ris","mode":"fixed","candidates":2.5,"samples":1.5})",
          R"({"type":"ris","mode":"robust","budget":4,"costs":{"t_x_ns":40,"t_y_ns":300}})",
          R"({"type":"ris","mode":"optimal","budget":4,"costs":{"t_x_ns":40,"t_y_ns":300}})"})
        expectSamePixels("ris_fig4_dragon_env.json", integrator, integrator, 4, 1, 2);
}

}  // namespace
}  // namespace rr::test
