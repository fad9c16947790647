// The same scene, seed and spp give bit-identical pixels for any thread count and from run
// to run: random numbers are indexed by (pixel, sample, decision, seed), never by thread, and
// each pixel accumulates its samples in index order.
#include <gtest/gtest.h>

#include "support/scene_testing.h"

namespace rr::test {
namespace {

void expectIdentical(const Film& a, const Film& b) {
    ASSERT_EQ(a.width(), b.width());
    ASSERT_EQ(a.height(), b.height());
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            ASSERT_EQ(a.mean(x, y), b.mean(x, y)) << "pixel " << x << "," << y;
            ASSERT_EQ(a.varianceOfMean(x, y), b.varianceOfMean(x, y)) << "pixel " << x << "," << y;
            ASSERT_EQ(a.sampleCount(x, y), b.sampleCount(x, y));
        }
}

class Determinism : public ::testing::TestWithParam<std::string> {};

// 50×37 is not a multiple of the 16-pixel tile, so partial tiles are covered too.
TEST_P(Determinism, OneAndTwoThreadsGiveIdenticalPixels) {
    const LoadedScene scene =
        loadSceneFile("cornell_spheres.json",
                      {"/render/resolution=[50,37]", "/render/sampler=\"" + GetParam() + "\""});
    const TestRender one = renderScene(scene, 12, 7, /*threads=*/1);
    const TestRender two = renderScene(scene, 12, 7, /*threads=*/2);
    const TestRender again = renderScene(scene, 12, 7, /*threads=*/2);
    expectIdentical(one.film, two.film);
    expectIdentical(two.film, again.film);
    EXPECT_EQ(one.stats.rays.total(), two.stats.rays.total());
}

TEST_P(Determinism, DifferentSeedsGiveDifferentImages) {
    const LoadedScene scene =
        loadSceneFile("cornell_spheres.json",
                      {"/render/resolution=[16,16]", "/render/sampler=\"" + GetParam() + "\""});
    const TestRender a = renderScene(scene, 4, 1), b = renderScene(scene, 4, 2);
    int differing = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x)
            differing += !(a.film.mean(x, y) == b.film.mean(x, y));
    EXPECT_GT(differing, 200);
}

INSTANTIATE_TEST_SUITE_P(Samplers, Determinism,
                         ::testing::Values("independent", "stratified", "hammersley"),
                         [](const auto& param) { return param.param; });

// TAIS makes each pixel depend on the ones scanned before it; fixed bands of rows (not the thread
// count) decide what is scanned together, so one, two and three threads agree. 37 rows in bands
// of 8 leave a short last band; auto enables the maps the scene has (light selection, point on
// light on the area light, bifurcation on the glass sphere, scatter direction).
TEST(Determinism, TaisBandsGiveIdenticalPixelsForAnyThreadCount) {
    const LoadedScene scene = loadSceneFile(
        "cornell_spheres.json",
        {"/render/resolution=[50,37]", R"(/integrator={"type":"tais","band_rows":8})"});
    const TestRender one = renderScene(scene, 12, 7, /*threads=*/1);
    const TestRender two = renderScene(scene, 12, 7, /*threads=*/2);
    const TestRender three = renderScene(scene, 12, 7, /*threads=*/3);
    expectIdentical(one.film, two.film);
    expectIdentical(one.film, three.film);
    EXPECT_EQ(one.stats.rays.total(), three.stats.rays.total());
}

// Warm-up rows are scanned by the band that uses them, whichever thread runs it.
TEST(Determinism, TaisWarmupRowsKeepPixelsIdenticalForAnyThreadCount) {
    const LoadedScene scene =
        loadSceneFile("cornell_spheres.json",
                      {"/render/resolution=[50,37]",
                       R"(/integrator={"type":"tais","band_rows":8,"band_warmup_rows":3})"});
    const TestRender one = renderScene(scene, 12, 7, /*threads=*/1);
    const TestRender two = renderScene(scene, 12, 7, /*threads=*/2);
    expectIdentical(one.film, two.film);
    // The warm-up changes what later bands learn, and so their pixels.
    const LoadedScene cold =
        loadSceneFile("cornell_spheres.json",
                      {"/render/resolution=[50,37]",
                       R"(/integrator={"type":"tais","band_rows":8,"band_warmup_rows":0})"});
    const TestRender without = renderScene(cold, 12, 7, /*threads=*/2);
    EXPECT_EQ(one.film.mean(0, 0), without.film.mean(0, 0)) << "the first band has no warm-up";
    int differing = 0;
    for (int x = 0; x < 50; ++x)
        differing += !(one.film.mean(x, 20) == without.film.mean(x, 20));
    EXPECT_GT(differing, 25);
}

}  // namespace
}  // namespace rr::test
