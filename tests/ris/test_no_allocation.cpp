// RIS draws many candidates per shading point: drawing them, evaluating ĝ and resampling must
// not touch the heap (the issue's performance requirement; an allocation per candidate would
// dominate T_X). Counted by replacing the global operator new in this test program.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "support/scene_testing.h"

namespace {
std::atomic<uint64_t> allocations{0};
}  // namespace

void* operator new(std::size_t size) {
    ++allocations;
    if (void* p = std::malloc(size ? size : 1)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

namespace rr::test {
namespace {

// Allocations made while the integrator estimates every pixel of a 16 × 16 image 4 times
// (after one warm-up pass, so that lazily built state does not count).
uint64_t allocationsWhileEstimating(const std::string& file, const std::string& integrator) {
    const LoadedScene s =
        loadSceneFile(file, {"/render/resolution=[16,16]", "/integrator=" + integrator});
    const auto& estimator = dynamic_cast<const SampleIntegrator&>(*s.integrator);
    const Sampler sampler(SamplerType::Independent, 1, 4);
    RayCounters rays;
    Rgb sum(0.0f);
    uint64_t before = 0;
    for (uint32_t pass = 0; pass < 5; ++pass) {
        if (pass == 1) before = allocations.load();
        for (uint32_t pixel = 0; pixel < 256; ++pixel)
            sum += estimator.estimate(*s.scene, int(pixel % 16), int(pixel / 16),
                                      sampler.at(pixel, pass), rays);
    }
    EXPECT_TRUE(sum.isFinite());
    EXPECT_GT(rays.shadow + rays.extension, 0u);
    return allocations.load() - before;
}

TEST(RisAllocations, CandidatesFromLightsAllocateNothing) {
    EXPECT_EQ(allocationsWhileEstimating(
                  "ris_fig4_dragon_env.json",
                  R"({"type":"ris","mode":"fixed","candidates":32,"samples":2.5})"),
              0u);
}

TEST(RisAllocations, CandidatesFromTheLightsStandInsAllocateNothing) {
    EXPECT_EQ(allocationsWhileEstimating(
                  "ris_fig4_dragon_env.json",
                  R"({"type":"ris","mode":"fixed","source":"light_proxy","candidates":32})"),
              0u);
}

TEST(RisAllocations, CandidatesFromDirectionsAllocateNothing) {
    EXPECT_EQ(allocationsWhileEstimating(
                  "ris_fig5_cook_torrance_sphere.json",
                  R"({"type":"ris","mode":"fixed","source":"uniform_hemisphere","candidates":20})"),
              0u);
}

// The counter works: a render allocates (its film, its threads' work lists).
TEST(RisAllocations, NegativeControlCountsAllocations) {
    const uint64_t before = allocations.load();
    const LoadedScene s =
        loadSceneFile("ris_fig5_diffuse_sphere.json", {"/render/resolution=[8,8]"});
    (void)renderScene(s, 1);
    EXPECT_GT(allocations.load(), before);
}

}  // namespace
}  // namespace rr::test
