// The environment lights' direction samplers other than the map's own (env_sampling.h):
// `cosine` (pbrt-v1's `infinite`: cosine-weighted about the receiver's shading normal over both
// hemispheres, uniform without a normal) and `uniform`. χ² of the directions against the
// claimed density (a tilted normal, no normal, uniform), with a density that ignores the lower
// hemisphere rejected; the density integrates to one; the inverse maps samples back to their
// coordinates. In renders, each of the three gives the same image (Šidák-corrected z-tests)
// under every estimator that weighs light samples by their density (MIS, TAIS's inverted
// light samples, PMC-HI, RIS's mixture): the weights use the same normal as the samples, or
// the image would move.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene/lights/env_sampling.h"
#include "support/chi2.h"
#include "support/histograms.h"
#include "support/maps.h"
#include "support/mean_agreement.h"
#include "support/scene_testing.h"
#include "support/scratch.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

const Chi2Family kChi2(4);

struct Sampler {
    const char* name;
    EnvSampling how;
    LightReference reference;
};

const Vec3 kTilted = normalize(Vec3(0.3f, -0.5f, 0.8f));
const Sampler kSamplers[] = {
    {"cosine_tilted_normal", EnvSampling::Cosine, LightReference(Vec3(1, 2, 3), kTilted)},
    {"cosine_without_normal", EnvSampling::Cosine, LightReference(Vec3(1, 2, 3))},
    {"uniform", EnvSampling::Uniform, LightReference(Vec3(1, 2, 3), kTilted)},
};

constexpr uint64_t kDraws = 400000;

DirectionHistogram drawDirections(const Sampler& s, uint64_t seed) {
    DirectionHistogram h(24, 48);
    for (uint64_t i = 0; i < kDraws; ++i) {
        Vec3 w;
        float pdf;
        if (sampleEnvDirection(s.how, s.reference, uniform2(seed, i), &w, &pdf)) h.add(w);
    }
    return h;
}

class EnvDirectionSampling : public ::testing::TestWithParam<Sampler> {};

TEST_P(EnvDirectionSampling, DirectionsFollowTheDensity) {
    const Sampler& s = GetParam();
    const DirectionHistogram h = drawDirections(s, 7);
    const auto pdf = [&](const Vec3& w) { return double(envDirectionPdf(s.how, s.reference, w)); };
    kChi2.expectFits(chi2GoodnessOfFit(h.counts(), h.expected(pdf, kDraws)), s.name);
}

TEST_P(EnvDirectionSampling, TheDensityIntegratesToOne) {
    const Sampler& s = GetParam();
    const DirectionHistogram grid(24, 48);
    const auto pdf = [&](const Vec3& w) { return double(envDirectionPdf(s.how, s.reference, w)); };
    double total = 0;
    for (double mass : grid.expected(pdf, 1.0))
        total += mass;
    EXPECT_NEAR(total, 1.0, 1e-4) << s.name;
}

TEST_P(EnvDirectionSampling, TheInverseMapsSamplesBack) {
    const Sampler& s = GetParam();
    int checked = 0;
    for (uint64_t i = 0; i < 2000; ++i) {
        const Vec2 u = uniform2(11, i);
        Vec3 w;
        float pdf;
        if (!sampleEnvDirection(s.how, s.reference, u, &w, &pdf)) continue;
        Vec2 back;
        ASSERT_TRUE(invertEnvDirection(s.how, s.reference, w, &back)) << s.name << " at " << i;
        // The sampled direction again from the recovered u (u itself may differ where the map
        // is not injective: the disc's centre, the sphere's poles).
        Vec3 again;
        ASSERT_TRUE(sampleEnvDirection(s.how, s.reference, back, &again, &pdf));
        // Float round trips through the disc: z = √(1 − r²) is steep at the rim, where an error
        // of ~1e-7 in r becomes ~3e-4 in the direction.
        EXPECT_LT(length(again - w), 2e-3f) << s.name << " at u = " << u.x << ", " << u.y;
        ++checked;
    }
    EXPECT_GT(checked, 1990);
}

INSTANTIATE_TEST_SUITE_P(Samplers, EnvDirectionSampling, ::testing::ValuesIn(kSamplers),
                         [](const auto& p) { return std::string(p.param.name); });

// Negative control: cosine sampling with its density read as one hemisphere only (the
// classical mistake of a cosine-hemisphere pdf) must be rejected.
TEST(EnvDirectionSamplingNegativeControl, AOneHemisphereDensityIsRejected) {
    const Sampler& s = kSamplers[0];
    const DirectionHistogram h = drawDirections(s, 7);
    const auto wrong = [&](const Vec3& w) {
        return dot(w, kTilted) > 0 ? 2.0 * envDirectionPdf(s.how, s.reference, w) : 0.0;
    };
    kChi2.expectRejects(chi2GoodnessOfFit(h.counts(), h.expected(wrong, kDraws)));
}

// A diffuse sphere and a glossy floor under a smooth lat-long map (bright sky, dim ground):
// the image must not depend on how the map is sampled.
std::string sceneText(const std::string& integrator, const std::string& sampling,
                      const std::string& mapFile) {
    return R"({"render": {"resolution": [20, 20], "max_depth": 3},
        "integrator": )" +
           integrator + R"(,
        "camera": {"position": [0, 2.5, 3], "look_at": [0, -0.3, 0], "fov": 40},
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.7,
                    "material": {"type": "lambert", "albedo": 0.7}},
                   {"type": "quad", "corner": [-2, -0.7, 2], "edge_u": [4, 0, 0], "edge_v": [0, 0, -4],
                    "material": {"type": "phong", "diffuse": 0.3, "specular": 0.3,
                                 "exponent": 20}}],
        "lights": [{"type": "environment", "file": ")" +
           mapFile + R"(", "layout": "latlong", "sampling": ")" + sampling + R"("}]})";
}

TEST(EnvSamplingInRenders, EverySamplerGivesTheSameImage) {
    const auto file = writeRgbExr(scratchDirectory() / "sky.exr", 64, 32, [](int, int row) {
        const float up = 1.0f - (float(row) + 0.5f) / 32.0f;  // 1 at the zenith row
        return Rgb(0.2f + 2.0f * up * up, 0.3f + 1.5f * up, 0.4f + up);
    });
    // Every consumer of light densities: MIS in direct and path_mis, light sampling alone,
    // TAIS's point-on-light map (it inverts the samples), PMC-HI's mixture, RIS's mixture
    // source (light samples and BSDF samples weighed by the light's density).
    const char* integrators[] = {
        R"({"type": "direct", "strategy": "mis"})",
        R"({"type": "direct", "strategy": "light"})",
        R"({"type": "path_mis"})",
        R"({"type": "tais", "maps": ["point_on_light"]})",
        R"({"type": "direct", "estimator": {"type": "pmc_hi"}})",
        R"({"type": "direct", "estimator": {"type": "ris", "source": "mixture", "candidates": 4}})"};
    const char* samplings[] = {"luminance", "cosine", "uniform"};
    const double z = zThreshold(sidakAlpha(0.01, 6 * 3 * 3));
    uint32_t seed = 100;
    for (const char* integrator : integrators) {
        std::vector<TestRender> renders;
        for (const char* sampling : samplings)
            renders.push_back(renderScene(
                loadSceneText(sceneText(integrator, sampling, file.string())), 256, seed++));
        expectImageMeansAgreePairwise(renders, {samplings, samplings + 3}, z, integrator);
    }
}

}  // namespace
}  // namespace rr::test
