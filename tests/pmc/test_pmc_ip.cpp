// PMC-IP (Lai et al. 2007 §4): the adaptation's α, deterministic mixture sampling's counts, the
// unbiasedness of the iterations' image (and the bias of the pooled one), determinism for any
// thread count, and bad settings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "config/config_error.h"
#include "math/tvi.h"
#include "support/chi2.h"
#include "support/scene_testing.h"
#include "techniques/pmc/mixture_allocation.h"

namespace rr::test {
namespace {

using pmc::mixtureCounts;
using pmc::mixtureWeights;

// α sums to one, never falls below ε/|P|, and above that floor is proportional to σ²/tvi(L).
TEST(PmcIpAdaptation, WeightsAreTheDefensiveMixtureOfVarianceOverTvi) {
    const std::vector<double> variance = {0.0, 0.01, 0.04, 0.01, 0.0};
    const std::vector<double> luminance = {0.5, 0.5, 0.5, 0.05, 2.0};
    const double epsilon = 0.01, scale = kDefaultCdPerUnit;
    const std::vector<double> alpha = mixtureWeights(variance, luminance, epsilon, scale);
    EXPECT_NEAR(std::accumulate(alpha.begin(), alpha.end(), 0.0), 1.0, 1e-12);
    const double floor = epsilon / 5;
    EXPECT_DOUBLE_EQ(alpha[0], floor);
    EXPECT_DOUBLE_EQ(alpha[4], floor);
    // Same luminance: the shares above the floor go as the variances.
    EXPECT_NEAR((alpha[2] - floor) / (alpha[1] - floor), 4.0, 1e-9);
    // Same variance, darker pixel: larger by the ratio of the thresholds.
    const double tviRatio = photopicTvi(0.5 * scale) / photopicTvi(0.05 * scale);
    EXPECT_NEAR((alpha[3] - floor) / (alpha[1] - floor), tviRatio, 1e-9);
    EXPECT_GT(tviRatio, 1.0);
}

TEST(PmcIpAdaptation, AFlatImageGetsUniformWeights) {
    const std::vector<double> alpha = mixtureWeights({0, 0, 0, 0}, {1, 0, 2, 3}, 0.01, 100);
    for (double a : alpha)
        EXPECT_DOUBLE_EQ(a, 0.25);
}

// Each pixel gets ⌊Nα⌋ or ⌈Nα⌉ samples, N in all, and over offsets u spread evenly on [0, 1)
// the mean count is Nα (the expectation DMS promises, here exactly up to the offsets' grid).
TEST(PmcIpAllocation, CountsAreFloorOrCeilingWithExpectationNAlpha) {
    std::vector<double> alpha(97);
    for (size_t k = 0; k < alpha.size(); ++k)
        alpha[k] = 1.0 + std::sin(double(k)) * 0.9 + (k % 7 == 0 ? 5.0 : 0.0);
    const double sum = std::accumulate(alpha.begin(), alpha.end(), 0.0);
    for (double& a : alpha)
        a /= sum;
    const uint64_t total = 97 * 4 + 3;
    constexpr int kOffsets = 4096;
    std::vector<double> meanCount(alpha.size(), 0.0);
    std::vector<uint32_t> counts(alpha.size());
    for (int i = 0; i < kOffsets; ++i) {
        mixtureCounts(alpha, total, (i + 0.5) / kOffsets, counts);
        uint64_t drawn = 0;
        for (size_t k = 0; k < alpha.size(); ++k) {
            const double expected = double(total) * alpha[k];
            ASSERT_GE(counts[k], std::floor(expected)) << k;
            ASSERT_LE(counts[k], std::ceil(expected)) << k;
            drawn += counts[k];
            meanCount[k] += double(counts[k]) / kOffsets;
        }
        ASSERT_EQ(drawn, total) << "offset " << i;
    }
    for (size_t k = 0; k < alpha.size(); ++k)
        EXPECT_NEAR(meanCount[k], double(total) * alpha[k], 1.0 / kOffsets) << k;
}

constexpr const char* kScene = "pmc_fig6_checker_floor.json";
constexpr int kSize = 32, kBlock = 8;
constexpr uint32_t kSeeds = 1024;

constexpr const char* kDirectMis =
    R"({"type":"direct","strategy":"mis","light_samples":1,"bsdf_samples":1})";
// §6.1's feedback: PMC-HI at the path tracer's first hits starts from the pixel's α so far.
constexpr const char* kPathPmcHiFeedback =
    R"({"type":"path_mis","estimator":{"type":"pmc_hi","feedback":true}})";

std::string pmcIp(const std::string& image, const std::string& integrator = kDirectMis) {
    return R"(/integrator={"type":"pmc_ip","initial_spp":2,"iteration_spp":4,"image":")" + image +
           R"(","integrator":)" + integrator + "}";
}

LoadedScene checkerFloor(const std::vector<std::string>& extra) {
    std::vector<std::string> overrides = {"/render/resolution=[32,32]"};
    overrides.insert(overrides.end(), extra.begin(), extra.end());
    return loadSceneFile(kScene, overrides);
}

// Mean of channel c over a block of a row-major image.
double blockMean(const std::vector<Rgb>& image, int c, int x0, int y0, int x1, int y1) {
    double sum = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            sum += image[size_t(y) * kSize + x][c];
    return sum / double((x1 - x0) * (y1 - y0));
}

// The image of a pmc_ip render: the integrator's estimates, or for `pooled` the film's means.
std::vector<Rgb> pmcImage(const LoadedScene& scene, const TestRender& render) {
    std::vector<Rgb> image = scene.integrator->pixelEstimates().values;
    if (!image.empty()) return image;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            image.push_back(render.film.mean(x, y));
    return image;
}

// The images of kSeeds renders against a long uniform render, for the image mean and each
// 8 × 8 block mean of each channel: the standard error of the renders' mean comes from their
// spread over seeds (a t statistic with kSeeds − 1 degrees of freedom), the reference's from
// its pixel variances. Returns the largest |t| and where.
double largestT(const LoadedScene& scene, uint32_t spp, std::string* where) {
    const TestRender reference = renderScene(
        checkerFloor({R"(/integrator={"type":"direct","strategy":"mis"})"}), 16384, 1000);
    std::vector<std::vector<Rgb>> images;
    for (uint32_t seed = 1; seed <= kSeeds; ++seed) {
        const TestRender render = renderScene(scene, spp, seed);
        images.push_back(pmcImage(scene, render));
        if (images.back().size() != size_t(kSize * kSize)) {
            ADD_FAILURE() << "an image of " << images.back().size() << " pixels";
            return 0;
        }
    }
    struct Block {
        int x0, y0, x1, y1;
    };
    std::vector<Block> blocks{{0, 0, kSize, kSize}};
    for (int y = 0; y < kSize; y += kBlock)
        for (int x = 0; x < kSize; x += kBlock)
            blocks.push_back({x, y, x + kBlock, y + kBlock});
    double worst = 0;
    for (const Block& b : blocks)
        for (int c = 0; c < 3; ++c) {
            double sum = 0, squares = 0;
            for (const auto& image : images) {
                const double m = blockMean(image, c, b.x0, b.y0, b.x1, b.y1);
                sum += m;
                squares += m * m;
            }
            const double n = kSeeds, mean = sum / n;
            const double variance = (squares - n * mean * mean) / (n - 1);
            const Estimate r = regionMean(reference.film, c, b.x0, b.y0, b.x1, b.y1);
            const double t = std::abs(mean - r.mean) /
                             std::sqrt(variance / n + r.standardError * r.standardError);
            if (t <= worst) continue;
            worst = t;
            *where = "channel " + std::to_string(c) + " block at (" + std::to_string(b.x0) + ", " +
                     std::to_string(b.y0) + "): " + std::to_string(mean) + " against " +
                     std::to_string(r.mean);
        }
    return worst;
}

// The unbiased cases (MIS, PMC-HI with feedback) × channels × (image + blocks).
int tests() {
    return 2 * 3 * (1 + (kSize / kBlock) * (kSize / kBlock));
}

double threshold() {
    // The unbiased case; the negative controls only need to exceed the same threshold.
    return tThreshold(sidakAlpha(0.01, tests()), int(kSeeds) - 1);
}

struct Outcome {
    double t;
    std::string where;
};

// The 2 + 4 + 4-spp renders of the checker floor with `overrides` against the reference,
// printed.
Outcome compareAt10Spp(const std::vector<std::string>& overrides) {
    Outcome o;
    o.t = largestT(checkerFloor(overrides), 10, &o.where);
    std::printf("largest |t| %.2f (threshold %.2f) at %s\n", o.t, threshold(), o.where.c_str());
    return o;
}

// Unbiased: the mean over seeds of the iterations' image (2 + 4 + 4 spp) matches a long
// uniform render.
TEST(PmcIpUnbiased, TheIterationsImageMatchesALongUniformRender) {
    const Outcome o = compareAt10Spp({pmcIp("iterations")});
    EXPECT_LT(o.t, threshold()) << o.where;
}

// With §6.1's feedback under the path tracer (on this scene, whose only surface is the floor,
// it converges to the direct lighting): each iteration's PMC-HI estimates at first hits start
// from α fixed before the iteration, so the image stays unbiased.
TEST(PmcIpUnbiased, PmcHiWithFeedbackMatchesALongUniformRender) {
    const Outcome o = compareAt10Spp({pmcIp("iterations", kPathPmcHiFeedback)});
    EXPECT_LT(o.t, threshold()) << o.where;
}

// The test's power: with a floor 2.5 % darker (both kinds of square) the same comparison must
// fail.
TEST(PmcIpUnbiased, NegativeControlDarkerSquaresAreRejected) {
    const Outcome o = compareAt10Spp({pmcIp("iterations"), "/materials/diffuse/albedo=0.53625",
                                      "/materials/glossy_rough/reflectance=0.975",
                                      "/materials/glossy_sharp/reflectance=0.975"});
    EXPECT_GT(o.t, threshold()) << o.where;
}

// Pooling all a pixel's samples is biased: a pixel whose first samples missed the lights'
// reflection looks flat, gets the defensive share only and keeps its dark estimate (measured:
// a block 21 % dark).
TEST(PmcIpUnbiased, NegativeControlThePooledImageIsRejected) {
    const Outcome o = compareAt10Spp({pmcIp("pooled")});
    EXPECT_GT(o.t, threshold()) << o.where;
}

// The allocation depends on the film only, never on threads: the same pixels, bit for bit.
TEST(PmcIpDeterminism, ImagesAndCountsAreIdenticalOnOneAndTwoThreads) {
    const LoadedScene scene = checkerFloor({pmcIp("iterations")});
    const TestRender one = renderScene(scene, 14, 7, 1);
    const PixelEstimates a = scene.integrator->pixelEstimates();
    const TestRender two = renderScene(scene, 14, 7, 2);
    const PixelEstimates b = scene.integrator->pixelEstimates();
    ASSERT_EQ(a.values.size(), size_t(kSize * kSize));
    int varied = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const size_t k = size_t(y) * kSize + x;
            ASSERT_EQ(one.film.sampleCount(x, y), two.film.sampleCount(x, y));
            ASSERT_EQ(a.values[k], b.values[k]) << x << ", " << y;
            ASSERT_EQ(a.variances[k], b.variances[k]) << x << ", " << y;
            varied += one.film.sampleCount(x, y) != 14;
        }
    EXPECT_GT(varied, kSize * kSize / 4) << "the allocation should vary between pixels";
}

// Feedback acts (the same seed renders other pixels than without it) and, committed between
// iterations only, leaves every pixel bit-identical on one and two threads.
TEST(PmcIpFeedback, ChangesTheImageAndIsIdenticalOnOneAndTwoThreads) {
    const LoadedScene feedback = checkerFloor({pmcIp("iterations", kPathPmcHiFeedback)});
    const LoadedScene plain =
        checkerFloor({pmcIp("iterations", R"({"type":"path_mis","estimator":{"type":"pmc_hi"}})")});
    const TestRender film = renderScene(feedback, 10, 3, 1);
    const PixelEstimates one = feedback.integrator->pixelEstimates();
    renderScene(feedback, 10, 3, 2);
    const PixelEstimates two = feedback.integrator->pixelEstimates();
    renderScene(plain, 10, 3, 2);
    const PixelEstimates without = plain.integrator->pixelEstimates();
    ASSERT_EQ(one.values.size(), size_t(kSize * kSize));
    // Pixels that got samples after the initial image (which starts from no record) and whose
    // first hit is the floor: feedback must change almost all of them.
    int adapted = 0, changed = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const size_t k = size_t(y) * kSize + x;
            ASSERT_EQ(one.values[k], two.values[k]) << x << ", " << y;
            if (film.film.sampleCount(x, y) == 2 || one.values[k] == Rgb(0.0f)) continue;
            ++adapted;
            changed += !(one.values[k] == without.values[k]);
        }
    std::printf("%d of %d pixels changed\n", changed, adapted);
    EXPECT_GT(adapted, kSize * kSize / 8);
    EXPECT_GT(changed, adapted * 9 / 10);
}

// 11 spp with 2 initial samples and iterations of 4: 2 + 4 + 4 + 1, exactly 11 per pixel on
// average; fewer spp than the initial image is refused naming the setting.
TEST(PmcIpSettings, TheLastIterationTakesWhatIsLeftOfTheSpp) {
    const LoadedScene scene = checkerFloor({pmcIp("iterations")});
    const TestRender render = renderScene(scene, 11, 1);
    uint64_t samples = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            samples += render.film.sampleCount(x, y);
    EXPECT_EQ(samples, uint64_t(11 * kSize * kSize));
    EXPECT_EQ(scene.integrator->parameters()["iterations"], 4);
    try {
        renderScene(scene, 1, 1);
        FAIL() << "1 spp was accepted";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/render/spp");
    }
}

TEST(PmcIpSettings, AnIntegratorThatSchedulesItsOwnSamplesIsRefused) {
    try {
        checkerFloor({R"(/integrator={"type":"pmc_ip","integrator":{"type":"tais"}})"});
        FAIL() << "pmc_ip over tais was accepted";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/integrator/integrator");
    }
}

TEST(PmcIpSettings, OneInitialSampleGivesNoVarianceAndIsRefused) {
    try {
        checkerFloor(
            {R"(/integrator={"type":"pmc_ip","initial_spp":1,"integrator":{"type":"direct"}})"});
        FAIL() << "initial_spp 1 was accepted";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/integrator/initial_spp");
    }
}

}  // namespace
}  // namespace rr::test
