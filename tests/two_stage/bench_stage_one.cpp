// `make bench`: what two-stage sampling costs per shading point, against a shadow ray's cost
// (issue: "Stage 1 costs per primary ray"). At the first hit of each pixel centre of fig. 8's
// Blinn sphere and fig. 10's penumbrae (64 × 64, one thread), for N = 4, 16, 64 samples:
//  - stage 1: the partition (root, initial splits, peaks, cascades, N refinement splits, weights);
//  - stage 2: N warps down the tree to a texel;
//  - N shadow rays towards the warped directions;
// and the partition's size: regions, cascaded splits, f evaluations, depth. Timings are medians
// over 5 passes of per-pass means (no test asserts on them).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "integrators/direct_lighting.h"
#include "scene/lights/environment_map.h"
#include "support/scene_testing.h"
#include "techniques/two_stage/two_stage_estimator.h"

namespace rr::test {
namespace {

using Clock = std::chrono::steady_clock;
using two_stage::Partition;
using two_stage::TwoStageEstimator;
using two_stage::TwoStageSettings;

constexpr int kSize = 64, kPasses = 5;

struct Totals {
    double stageOne = 0, warps = 0, shadows = 0;  // seconds
    uint64_t points = 0, samples = 0;
    double regions = 0, cascades = 0, evaluations = 0, depth = 0;
};

double seconds(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

// One pass over the pixel centres: each stage timed around all shading points' work.
Totals pass(const LoadedScene& loaded, const TwoStageEstimator& estimator, uint32_t n) {
    const Scene& scene = *loaded.scene;
    const Sampler sampler(SamplerType::Independent, 1, 1);
    Totals t;
    Partition partition;
    std::vector<Vec3> directions(n);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const PixelSample sample = sampler.at(uint32_t(y * kSize + x), 0);
            StandardSampling standard(scene, sample);
            RayCounters rays;
            estimateAtFirstHit(scene, standard, x, y, rays, [&](ShadingPoint& point) {
                const auto a = Clock::now();
                if (!estimator.partitionAt(point, n, &partition)) return;
                const auto b = Clock::now();
                uint32_t warped = 0;
                for (uint32_t i = 0; i < n; ++i) {
                    const Vec2 u = point.decide2D(Decision::LightPoint, i, n);
                    int col, row;
                    double pdf;
                    if (estimator.warpDirection(partition, u.x, u.y, &directions[warped], &col,
                                                &row, &pdf))
                        ++warped;
                }
                const auto c = Clock::now();
                for (uint32_t i = 0; i < warped; ++i) {
                    LightSample ls;
                    estimator.map().aim(point.position(), directions[i], &ls);
                    float survival;
                    point.visibility(ls, true, &survival);
                }
                const auto d = Clock::now();
                t.stageOne += seconds(a, b);
                t.warps += seconds(b, c);
                t.shadows += seconds(c, d);
                t.samples += warped;
                ++t.points;
                t.regions += partition.stats().regions;
                t.cascades += partition.stats().cascades;
                t.evaluations += partition.stats().evaluations;
                t.depth += partition.depth();
            });
        }
    return t;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

void bench(const std::string& file) {
    const LoadedScene loaded =
        loadSceneFile(file, {"/render/resolution=[64,64]", "/camera/pixel_sample=\"centre\"",
                             R"(/integrator={"type":"direct","strategy":"mis"})"});
    std::printf("%s, %d x %d pixel centres, one thread:\n", file.c_str(), kSize, kSize);
    std::printf("  %3s | %12s %12s %12s | %10s | %8s %8s %8s %6s\n", "N", "stage 1 us", "warps us",
                "shadows us", "stage1/ray", "regions", "cascades", "f evals", "depth");
    for (const uint32_t n : {4u, 16u, 64u}) {
        TwoStageSettings settings;
        settings.samples = n;
        TwoStageEstimator estimator(settings);
        estimator.prepare(*loaded.scene, "/integrator/estimator");
        std::vector<double> one, warps, shadows;
        Totals t;
        for (int p = 0; p < kPasses; ++p) {
            t = pass(loaded, estimator, n);
            one.push_back(t.stageOne / double(t.points));
            warps.push_back(t.warps / double(t.points));
            shadows.push_back(t.shadows / double(t.points));
        }
        const double perRay = median(shadows) * double(t.points) / double(t.samples);
        const double points = double(t.points);
        std::printf("  %3u | %12.2f %12.2f %12.2f | %10.1f | %8.1f %8.1f %8.1f %6.1f\n", n,
                    median(one) * 1e6, median(warps) * 1e6, median(shadows) * 1e6,
                    median(one) / perRay, t.regions / points, t.cascades / points,
                    t.evaluations / points, t.depth / points);
    }
}

}  // namespace
}  // namespace rr::test

int main() {
    rr::test::bench("twostage_fig8_blinn.json");
    rr::test::bench("twostage_fig10_penumbrae.json");
    return 0;
}
