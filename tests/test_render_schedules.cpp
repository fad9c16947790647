// The render schedules (render/render_schedule.h): the visits each plans, and that every one
// renders the same pixels for any thread count with sample indices that continue from what a
// pixel already holds.
#include <gtest/gtest.h>

#include <atomic>

#include "render/iterated_allocation.h"
#include "render/scan_bands.h"
#include "render/uniform_passes.h"
#include "support/scene_testing.h"

namespace rr::test {
namespace {

// TAIS §3.3, "we scan back and forth": a band's rows alternate direction from its first row.
TEST(ScanBands, SerpentineVisitsAlternateFromTheFirstRow) {
    std::vector<PixelVisit> visits;
    serpentineVisits(3, 4, 7, 0, 2, true, &visits);
    const std::vector<std::pair<int, int>> expected = {{0, 4}, {1, 4}, {2, 4}, {2, 5},
                                                       {1, 5}, {0, 5}, {0, 6}};
    ASSERT_EQ(visits.size(), 9u);
    for (size_t i = 0; i < expected.size(); ++i)
        EXPECT_EQ(std::make_pair(visits[i].x, visits[i].y), expected[i]) << "position " << i;
}

// A band first scans its warm-up rows of the band above, with sample indices spp … 2 spp − 1
// that the film never keeps, and goes on in the direction the scan left off.
TEST(ScanBands, BandsStartWithDiscardedWarmupRowsFromTheBandAbove) {
    ScanBands bands(2, 7, /*spp=*/4, /*bandRows=*/3, /*warmupRows=*/2,
                    [](const Sampler&) { return std::unique_ptr<PixelRenderer>(); });
    Round round;
    ASSERT_TRUE(bands.nextRound(Film(2, 7), RoundTiming{}, &round));
    EXPECT_EQ(round.units, 3u);
    EXPECT_TRUE(round.interruptible);
    std::vector<PixelVisit> visits;
    bands.unitVisits(1, &visits);
    const std::vector<PixelVisit> expected = {
        {0, 1, 4, 4, false}, {1, 1, 4, 4, false}, {1, 2, 4, 4, false}, {0, 2, 4, 4, false},
        {0, 3, 0, 4, true},  {1, 3, 0, 4, true},  {1, 4, 0, 4, true},  {0, 4, 0, 4, true},
        {0, 5, 0, 4, true},  {1, 5, 0, 4, true}};
    EXPECT_EQ(visits, expected);
    bands.unitVisits(0, &visits);  // the first band has nothing above it
    EXPECT_EQ(visits.front(), (PixelVisit{0, 0, 0, 4, true}));
    // The last band, cut at the image's bottom: warm-up rows 4 and 5, then row 6, the scan's
    // third row, left to right.
    bands.unitVisits(2, &visits);
    ASSERT_EQ(visits.size(), 6u);
    EXPECT_EQ(visits.back(), (PixelVisit{1, 6, 0, 4, true}));
    EXPECT_FALSE(bands.nextRound(Film(2, 7), RoundTiming{}, &round)) << "one round";
}

// Without a time limit, uniform passes tile [0, spp) of every pixel exactly, growing while
// passes are fast.
TEST(UniformPasses, PassesCoverEverySampleIndexOnce) {
    const LoadedScene scene = loadSceneFile("cornell_spheres.json");
    const auto& integrator = dynamic_cast<const SampleIntegrator&>(*scene.integrator);
    UniformPasses passes(*scene.scene, integrator, 40, 20, /*spp=*/37, 0);
    EXPECT_EQ(passes.plannedSamples(), 40u * 20u * 37u);
    uint32_t next = 0;
    Round round;
    std::vector<PixelVisit> visits;
    const RoundTiming fast{0, 0, 1e-6, 800};
    while (passes.nextRound(Film(40, 20), fast, &round)) {
        EXPECT_EQ(round.units, 6u);  // 3 × 2 tiles of 16 × 16
        passes.unitVisits(5, &visits);
        ASSERT_EQ(visits.size(), 8u * 4u);  // the bottom-right tile is cut to 8 × 4
        EXPECT_EQ(visits.front().first, next);
        next += visits.front().count;
    }
    EXPECT_EQ(next, 37u);
}

// A variable allocation: every pixel gets 2 samples, then one more per 0.05 of its sample
// standard deviation (luminance), up to 6.
bool allocateByNoise(const Film& film, int iteration, std::vector<uint32_t>* counts) {
    if (iteration == 2) return false;
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const double deviation =
                std::sqrt(film.varianceOfMean(x, y).luminance() * film.sampleCount(x, y));
            (*counts)[size_t(y) * film.width() + x] =
                iteration == 0 ? 2u : std::min(6u, uint32_t(deviation / 0.05));
        }
    return true;
}

Film renderAllocated(const LoadedScene& scene, int threads, RenderStats* stats) {
    const auto& integrator = dynamic_cast<const SampleIntegrator&>(*scene.integrator);
    IteratedAllocation schedule(
        *scene.scene, integrator, scene.render.width, scene.render.height, 0,
        [](const Film& film, int iteration, IteratedAllocation::Plan* plan) {
            plan->counts.resize(size_t(film.width()) * film.height());
            return allocateByNoise(film, iteration, &plan->counts);
        });
    Film film(scene.render.width, scene.render.height);
    RenderOptions options;
    options.threads = threads;
    options.seed = 3;
    *stats = render(schedule, options, film);
    return film;
}

// Each pixel's samples continue its sample indices: a pixel holding n samples holds exactly
// the estimates of indices 0 … n − 1, whatever the allocation, and the image is the same for
// one and two threads.
TEST(IteratedAllocation, PixelsContinueTheirSampleIndicesOnAnyThreadCount) {
    const LoadedScene scene = loadSceneFile("cornell_spheres.json", {"/render/resolution=[24,20]"});
    RenderStats one, two;
    const Film a = renderAllocated(scene, 1, &one), b = renderAllocated(scene, 2, &two);
    EXPECT_TRUE(one.complete);
    const auto& integrator = dynamic_cast<const SampleIntegrator&>(*scene.integrator);
    const Sampler sampler(SamplerType::Independent, 3, 16);
    int varied = 0;
    for (int y = 0; y < 20; ++y)
        for (int x = 0; x < 24; ++x) {
            ASSERT_EQ(a.sampleCount(x, y), b.sampleCount(x, y));
            ASSERT_EQ(a.mean(x, y), b.mean(x, y)) << x << ", " << y;
            const uint32_t n = a.sampleCount(x, y);
            varied += n != 2;
            Film direct(1, 1);
            RayCounters rays;
            for (uint32_t s = 0; s < n; ++s)
                direct.add(0, 0,
                           integrator.estimate(*scene.scene, x, y,
                                               sampler.at(uint32_t(y * 24 + x), s), rays));
            EXPECT_EQ(direct.mean(0, 0), a.mean(x, y)) << x << ", " << y;
        }
    EXPECT_GT(varied, 24 * 20 / 10) << "the allocation should vary between pixels";
}

// A cancelled render of an interruptible round stops between units and says the image is
// incomplete.
TEST(RenderLoop, CancelledBandsLeaveTheImageIncomplete) {
    const LoadedScene scene = loadSceneFile(
        "cornell_spheres.json",
        {"/render/resolution=[16,16]", R"(/integrator={"type":"tais","band_rows":1})"});
    const std::unique_ptr<RenderSchedule> schedule = scene.schedule(scene.scheduleInputs(1, 0));
    std::atomic<bool> cancel{true};
    RenderOptions options;
    options.cancel = &cancel;
    Film film(16, 16);
    const RenderStats stats = render(*schedule, options, film);
    EXPECT_TRUE(stats.interrupted);
    EXPECT_FALSE(stats.complete);
    EXPECT_EQ(stats.spp, 0u);
}

}  // namespace
}  // namespace rr::test
