// Different unbiased estimators of the same image must agree in mean: `path` vs `path_mis` on
// the default scene (all light transport), the three `direct` strategies on it (direct
// lighting only), and `path_mis` assembled from its public pieces with a light-selection policy
// of its own. Differences are judged against the standard errors from the variance channel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "integrators/path_tracer.h"
#include "loader/factories.h"
#include "support/chi2.h"
#include "support/mean_agreement.h"
#include "support/scene_testing.h"

namespace rr::test {
namespace {

// z of the difference of two independent estimates.
double differenceZ(const Estimate& a, const Estimate& b) {
    return (a.mean - b.mean) /
           std::sqrt(a.standardError * a.standardError + b.standardError * b.standardError);
}

const std::vector<std::string> kSmall = {"/render/resolution=[32,32]"};

TEST(IntegratorAgreement, PathAndPathMisAgreeOnTheDefaultSceneWithinThreeStandardErrors) {
    auto overrides = kSmall;
    overrides.push_back("/integrator/type=\"path\"");
    const LoadedScene path = loadSceneFile("cornell_spheres.json", overrides);
    overrides.back() = "/integrator/type=\"path_mis\"";
    const LoadedScene mis = loadSceneFile("cornell_spheres.json", overrides);
    const TestRender a = renderScene(path, 1024, /*seed=*/11);
    const TestRender b = renderScene(mis, 1024, /*seed=*/12);
    for (int c = 0; c < 3; ++c) {
        const Estimate ea = imageMean(a.film, c), eb = imageMean(b.film, c);
        EXPECT_LT(std::abs(differenceZ(ea, eb)), 3.0)
            << "channel " << c << ": path " << ea.mean << " ± " << ea.standardError << ", path_mis "
            << eb.mean << " ± " << eb.standardError;
    }
}

TEST(IntegratorAgreement, DirectLightingStrategiesAgree) {
    // Three pairwise comparisons × 3 channels, family-wise level 0.01.
    const double z = zThreshold(sidakAlpha(0.01, 9));
    std::vector<TestRender> renders;
    uint32_t seed = 20;
    for (const char* strategy : {"light", "bsdf", "mis"}) {
        auto overrides = kSmall;
        overrides.push_back("/integrator={\"type\":\"direct\",\"strategy\":\"" +
                            std::string(strategy) + "\",\"light_samples\":2,\"bsdf_samples\":3}");
        renders.push_back(
            renderScene(loadSceneFile("cornell_spheres.json", overrides), 512, seed++));
    }
    for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j)
            for (int c = 0; c < 3; ++c) {
                const Estimate a = imageMean(renders[i].film, c), b = imageMean(renders[j].film, c);
                EXPECT_LT(std::abs(differenceZ(a, b)), z)
                    << "strategies " << i << " vs " << j << ", channel " << c << ": " << a.mean
                    << " ± " << a.standardError << " vs " << b.mean << " ± " << b.standardError;
            }
}

// Next-event estimation at path vertices by any estimator estimates the same image: light
// sampling alone (the emission the path finds at non-specular vertices left out) and MIS
// with two light samples per vertex against the default (MIS, one light sample).
TEST(IntegratorAgreement, PathMisEstimatorsAgree) {
    const double z = zThreshold(sidakAlpha(0.01, 6));  // two comparisons × 3 channels
    std::vector<TestRender> renders;
    uint32_t seed = 30;
    for (const char* estimator :
         {R"({"type":"mis"})", R"({"type":"light"})", R"({"type":"mis","light_samples":2})"}) {
        auto overrides = kSmall;
        overrides.push_back(std::string(R"(/integrator={"type":"path_mis","estimator":)") +
                            estimator + "}");
        renders.push_back(
            renderScene(loadSceneFile("cornell_spheres.json", overrides), 512, seed++));
    }
    for (int i = 1; i < 3; ++i)
        for (int c = 0; c < 3; ++c) {
            const Estimate a = imageMean(renders[0].film, c), b = imageMean(renders[i].film, c);
            EXPECT_LT(std::abs(differenceZ(a, b)), z)
                << "estimator " << i << ", channel " << c << ": " << a.mean << " ± "
                << a.standardError << " vs " << b.mean << " ± " << b.standardError;
        }
}

// The default roulette (from the first vertex, only below survival 0.25), the throughput rule
// played always from the fourth vertex (the former default), a fixed survival probability
// (pbrt-v1's 0.5, `rr_survival`) from the second vertex, and the throughput rule only below 0.05
// estimate the same image.
TEST(IntegratorAgreement, RussianRouletteRulesAgreeWithEachOther) {
    const double z = zThreshold(sidakAlpha(0.01, 6 * 3));  // 6 pairs × 3 channels
    std::vector<TestRender> renders;
    uint32_t seed = 50;
    for (const char* roulette :
         {"", R"(,"rr_depth":4,"rr_threshold":1)", R"(,"rr_depth":2,"rr_survival":0.5)",
          R"(,"rr_depth":1,"rr_threshold":0.05)"}) {
        auto overrides = kSmall;
        overrides.push_back(std::string(R"(/render={"resolution":[32,32],"max_depth":8)") +
                            roulette + "}");
        renders.push_back(
            renderScene(loadSceneFile("cornell_spheres.json", overrides), 512, seed++));
    }
    expectImageMeansAgreePairwise(
        renders, {"default", "throughput always from vertex 4", "fixed 0.5", "below 0.05"}, z,
        "cornell_spheres");
}

// One implementation of next-event estimation: `path_mis` whose estimator samples no light is
// `path` pixel for pixel, and `direct` with a named estimator is `direct` with the same
// strategy.
TEST(IntegratorAgreement, EstimatorsNamedTwoWaysRenderTheSamePixels) {
    const std::vector<std::pair<std::string, std::string>> pairs = {
        {R"({"type":"path"})", R"({"type":"path_mis","estimator":{"type":"bsdf"}})"},
        {R"({"type":"direct","strategy":"mis","light_samples":2,"bsdf_samples":3})",
         R"({"type":"direct","estimator":{"type":"mis","light_samples":2},"bsdf_samples":3})"}};
    for (const auto& [first, second] : pairs) {
        auto a = kSmall, b = kSmall;
        a.push_back("/integrator=" + first);
        b.push_back("/integrator=" + second);
        const TestRender ra = renderScene(loadSceneFile("cornell_spheres.json", a), 8, 5);
        const TestRender rb = renderScene(loadSceneFile("cornell_spheres.json", b), 8, 5);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                ASSERT_EQ(ra.film.mean(x, y), rb.film.mean(x, y))
                    << first << " at " << x << ", " << y;
    }
}

// MIS must not cost accuracy where light sampling is good: on the default scene the combined
// strategy's image-mean standard error is below BSDF sampling's (a sanity check that the
// weights are used, not a tuned threshold: for a small area light BSDF sampling is far worse).
TEST(IntegratorAgreement, DirectMisHasLowerErrorThanBsdfSamplingOnASmallLight) {
    auto render = [](const char* strategy) {
        auto overrides = kSmall;
        overrides.push_back("/integrator={\"type\":\"direct\",\"strategy\":\"" +
                            std::string(strategy) + "\"}");
        return renderScene(loadSceneFile("cornell_spheres.json", overrides), 256, 5);
    };
    const TestRender bsdf = render("bsdf"), mis = render("mis");
    EXPECT_LT(imageMean(mis.film, 1).standardError, imageMean(bsdf.film, 1).standardError);
}

// Next-event estimation's lights picked uniformly, whatever the scene's selection: the policy of
// renderer/README.md's worked example ("Building on path_mis").
class UniformLights {
  public:
    explicit UniformLights(const Scene& scene) : lights_(scene.lights()) {}
    const Light* select(float u, const Vec3& /*reference*/, float* pmf) const {
        if (lights_.empty()) return nullptr;
        *pmf = 1.0f / float(lights_.size());
        return lights_[std::min(size_t(u * float(lights_.size())), lights_.size() - 1)];
    }
    float pmf(const Light& /*light*/, const Vec3& /*reference*/) const {
        return 1.0f / float(lights_.size());
    }

  private:
    std::span<const Light* const> lights_;
};

// Negative controls: uniform draws whose probability is reported as the scene's (power)
// selection's by the draw and by pmf() (`Everywhere`), or by pmf() alone (`DensityOnly`), which
// weighs emission found by BSDF samples against light sampling: what a guide whose lightPdf()
// ignored its policy would do.
enum class Misreport { Everywhere, DensityOnly };
template <Misreport kWhere>
class MisreportedUniformLights {
  public:
    explicit MisreportedUniformLights(const Scene& scene)
        : uniform_(scene), selector_(scene.lightSelector()) {}
    const Light* select(float u, const Vec3& reference, float* pmf) const {
        const Light* light = uniform_.select(u, reference, pmf);
        if (light && kWhere == Misreport::Everywhere) *pmf = selector_.pmf(*light, reference);
        return light;
    }
    float pmf(const Light& light, const Vec3& reference) const {
        return selector_.pmf(light, reference);
    }

  private:
    UniformLights uniform_;
    const LightSelector& selector_;
};

// Hands each guide the scene's own selector, which as a policy needs more than the scene to be
// made from: path_mis assembled from the public pieces, MakeGuide included.
struct SceneSelectorGuide {
    StandardSamplingWith<const LightSelector&> operator()(const Scene& scene,
                                                          const PixelSample& sample) const {
        return {scene, sample, scene.lightSelector()};
    }
};

// Two lights of unequal power under power selection: a large dim quad close above a diffuse
// floor, which lights the image and which BSDF samples find too (MIS weights count), and a
// small bright quad turned away from everything, which power selection picks with probability
// 10/11 and uniform selection with 1/2. Path settings are the defaults, as renderAssembled()
// builds them.
const char* const kUnequalLights = R"({
  "camera": { "type": "pinhole", "position": [0, 3, 3], "look_at": [0, 0, 0], "fov": 50 },
  "render": { "resolution": [24, 24], "light_selection": "power" },
  "integrator": { "type": "path_mis" },
  "shapes": [
    { "type": "quad", "corner": [-3, 0, 3], "edge_u": [6, 0, 0], "edge_v": [0, 0, -6],
      "material": { "type": "lambert", "albedo": 0.7 } },
    { "type": "quad", "corner": [-2, 0.2, -1], "edge_u": [0, 2, 0], "edge_v": [0, 0, 2],
      "emission": { "radiance": 1 } },
    { "type": "quad", "corner": [0, 1, -3.2], "edge_u": [0, 0.2, 0], "edge_v": [0.2, 0, 0],
      "emission": { "radiance": 1000 } }
  ]
})";

// `scene` rendered by PathTracer<Guide, MakeGuide> in place of its own integrator, with the
// estimator path_mis reads from an integrator object without one.
template <class Guide, class MakeGuide = ConstructGuide<Guide>>
TestRender renderAssembled(LoadedScene& scene, uint32_t spp, uint32_t seed) {
    const PathSettings path;
    const Json noEstimator = Json::object();
    ObjectReader json(noEstimator, "/integrator");
    BuiltIntegrator built = withUniformPasses(std::make_unique<PathTracer<Guide, MakeGuide>>(
        "assembled", path, IntegratorContext{path, techniqueRegistry()}.readEstimator(json)));
    built.integrator->prepare(*scene.scene);
    scene.integrator = std::move(built.integrator);
    scene.schedule = std::move(built.schedule);
    return renderScene(scene, spp, seed);
}

// The scene's selector handed in as a policy draws and weighs exactly as path_mis: the same
// pixels at the same seed.
TEST(IntegratorAgreement, PathMisAssembledFromItsPiecesRendersItsPixels) {
    const TestRender standard = renderScene(loadSceneText(kUnequalLights), 16, 7);
    LoadedScene scene = loadSceneText(kUnequalLights);
    const TestRender assembled =
        renderAssembled<StandardSamplingWith<const LightSelector&>, SceneSelectorGuide>(scene, 16,
                                                                                        7);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x)
            ASSERT_EQ(standard.film.mean(x, y), assembled.film.mean(x, y)) << x << ", " << y;
}

// The largest |z| over the channels between the image means of `standard` and of kUnequalLights
// rendered at `seed` with light-selection policy `Policy`, and those means in the worst channel.
template <LightSelectionPolicy Policy>
std::pair<double, std::string> disagreementWith(const TestRender& standard, uint32_t seed) {
    LoadedScene scene = loadSceneText(kUnequalLights);
    const TestRender other = renderAssembled<StandardSamplingWith<Policy>>(scene, 1024, seed);
    std::pair<double, std::string> worst{0, ""};
    for (int c = 0; c < 3; ++c) {
        const Estimate a = imageMean(standard.film, c), b = imageMean(other.film, c);
        const double z = std::abs(differenceZ(a, b));
        if (z < worst.first) continue;
        worst = {z, "channel " + std::to_string(c) + ": " + std::to_string(a.mean) + " ± " +
                        std::to_string(a.standardError) + " vs " + std::to_string(b.mean) + " ± " +
                        std::to_string(b.standardError)};
    }
    return worst;
}

// Uniform light selection through StandardSamplingWith estimates path_mis's image: its draws and
// both lightPdf()s follow the policy, so the MIS weights stay right. Both negative controls
// must fail the same test.
TEST(IntegratorAgreement, UniformLightSelectionPolicyAgreesWithPathMis) {
    const double z = zThreshold(sidakAlpha(0.01, 3));
    const TestRender standard = renderScene(loadSceneText(kUnequalLights), 1024, 61);
    const auto uniform = disagreementWith<UniformLights>(standard, 62);
    EXPECT_LT(uniform.first, z) << "path_mis vs uniform selection, " << uniform.second;
    const auto misreported =
        disagreementWith<MisreportedUniformLights<Misreport::Everywhere>>(standard, 63);
    EXPECT_GT(misreported.first, z)
        << "uniform draws reported as power selection went unnoticed, " << misreported.second;
    const auto misweighted =
        disagreementWith<MisreportedUniformLights<Misreport::DensityOnly>>(standard, 64);
    EXPECT_GT(misweighted.first, z)
        << "MIS weights against power selection's density went unnoticed, " << misweighted.second;
}

}  // namespace
}  // namespace rr::test
