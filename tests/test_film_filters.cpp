// Reconstruction filters and the splatting film (render/reconstruction_filter.h, render/film.h):
// the weights integrate to one and are pbrt-v1's, the "filter" key and its errors, a constant
// image through every filter, thread-count invariance, the fixed pass plan (an image reached by
// a time limit equals the fixed-spp image of its spp), the variance channel against the spread
// over seeds, and the filtered image's mean against a long render through the same filter.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "config/config_error.h"
#include "render/uniform_passes.h"
#include "sampling/hash.h"
#include "support/chi2.h"
#include "support/scene_testing.h"

namespace rr::test {
namespace {

FilterSettings mitchell(double radius = 2, double b = 1.0 / 3, double c = 1.0 / 3) {
    FilterSettings f;
    f.type = FilterType::Mitchell;
    f.radius = radius;
    f.b = b;
    f.c = c;
    return f;
}

FilterSettings gaussian(double radius = 2, double alpha = 2) {
    FilterSettings f;
    f.type = FilterType::Gaussian;
    f.radius = radius;
    f.alpha = alpha;
    return f;
}

std::vector<FilterSettings> someFilters() {
    return {FilterSettings{}, mitchell(),       mitchell(1.5),   mitchell(3.3, 0, 0.5),
            gaussian(),       gaussian(1, 0.5), gaussian(0.5, 8)};
}

// Composite Simpson's rule over [a, b] with n (even) intervals.
template <class F>
double simpson(const F& f, double a, double b, int n) {
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i)
        sum += f(a + i * h) * (i % 2 ? 4 : 2);
    return sum * h / 3;
}

// Every filter integrates to one over the line, its closed-form integral agrees with quadrature
// on arbitrary intervals, and the 2-D filter (their product) integrates to one too.
TEST(ReconstructionFilter, WeightsIntegrateToOne) {
    for (const FilterSettings& settings : someFilters()) {
        const ReconstructionFilter f(settings);
        const std::string what = f.parameters().dump();
        if (f.isBox()) {  // 1 on [−½, ½)
            EXPECT_EQ(f.integral1D(-2, 2), 1.0);
            EXPECT_DOUBLE_EQ(f.integral1D(-0.3, 0.9), 0.8);
            EXPECT_EQ(f.weight1D(-0.5), 1.0);
            EXPECT_EQ(f.weight1D(0.5), 0.0);
            continue;
        }
        const double r = settings.radius;
        auto w = [&](double d) { return f.weight1D(d); };
        // Piecewise smooth: Simpson on each piece (the Mitchell cubic changes at r/2).
        const double quadrature = simpson(w, -r, -r / 2, 2000) + simpson(w, -r / 2, 0, 2000) +
                                  simpson(w, 0, r / 2, 2000) + simpson(w, r / 2, r, 2000);
        EXPECT_NEAR(quadrature, 1.0, 1e-9) << what;
        EXPECT_NEAR(f.integral1D(-r - 1, r + 1), 1.0, 1e-12) << what;
        for (const auto& [a, b] :
             {std::pair{-0.3, 0.9}, std::pair{-r, 0.1}, std::pair{0.2, 0.45}}) {
            const double middle = 0.5 * (a + b);
            const double pieces = simpson(w, a, middle, 4000) + simpson(w, middle, b, 4000);
            EXPECT_NEAR(f.integral1D(a, b), pieces, 1e-6)
                << what << " on [" << a << ", " << b << "]";
        }
    }
}

// pbrt-v1's Mitchell filter (filters/mitchell.cpp: width 2, B = C = 1/3) evaluates
// Mitchell1D(2 d / width) in each axis; its values at these offsets, worked out by hand from
// Mitchell & Netravali's cubic in exact fractions, are ours: the default normalised filter of
// radius 2 is pbrt-v1's exactly.
TEST(ReconstructionFilter, MitchellIsPbrtV1s) {
    const ReconstructionFilter f(mitchell());
    const struct {
        double d, weight;
    } table[] = {{0, 8.0 / 9},
                 {0.25, 901.0 / 1152},
                 {0.5, 77.0 / 144},
                 {1, 1.0 / 18},
                 {1.25, -3.0 / 128},
                 {1.5, -5.0 / 144},
                 {1.75, -17.0 / 1152},
                 {2, 0},
                 {2.5, 0}};
    for (const auto& row : table) {
        EXPECT_NEAR(f.weight1D(row.d), row.weight, 1e-15) << row.d;
        EXPECT_NEAR(f.weight1D(-row.d), row.weight, 1e-15) << -row.d;
    }
    // The 2-D weight is the product (pbrt-v1's Evaluate(x, y)).
    ReconstructionFilter::Taps wx, wy;
    f.taps(0.5f, &wx);  // a sample at a pixel centre: offsets −2, −1, 0, 1, 2 to the centres
    f.taps(0.0f, &wy);  // on a pixel's edge: −1.5, −0.5, 0.5, 1.5, 2.5
    EXPECT_NEAR(wx.weight[2] * wy.weight[2], 8.0 / 9 * 77.0 / 144, 1e-15);
    EXPECT_NEAR(wx.weight[1] * wy.weight[0], 1.0 / 18 * -5.0 / 144, 1e-15);
    // Only the centres within the radius: −1, 0, 1 (±2 is on the edge, weight 0), and
    // −1.5 … 1.5.
    EXPECT_EQ(wx.first, 1);
    EXPECT_EQ(wx.last, 3);
    EXPECT_EQ(wy.first, 0);
    EXPECT_EQ(wy.last, 3);
    EXPECT_EQ(wy.weight[4], 0.0);  // 2.5 away
}

// pbrt-v1's Gaussian (filters/gaussian.cpp) is exp(−α d²) − exp(−α r²) per axis; ours is that
// over its integral.
TEST(ReconstructionFilter, GaussianIsPbrtV1sUpToItsNormalisation) {
    const double r = 2, alpha = 2;
    const ReconstructionFilter f(gaussian(r, alpha));
    auto pbrt = [&](double d) {
        return std::max(0.0, std::exp(-alpha * d * d) - std::exp(-alpha * r * r));
    };
    for (double d : {0.1, 0.5, 1.0, 1.7, 1.99, 2.5})
        EXPECT_NEAR(f.weight1D(d) / f.weight1D(0), pbrt(d) / pbrt(0), 1e-14) << d;
}

// The loader reads "filter" as a name or an object; bad values are errors naming the pointer.
TEST(ReconstructionFilter, FilterKeyAndItsErrors) {
    auto scene = [](const std::string& filter) {
        return R"({"render": {"resolution": [4, 4], "filter": )" + filter + R"(},
                   "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0], "fov": 40},
                   "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.5,
                               "emission": {"radiance": 1}}]})";
    };
    EXPECT_EQ(loadSceneText(scene(R"("mitchell")")).render.filter.type, FilterType::Mitchell);
    const LoadedScene g =
        loadSceneText(scene(R"({"type": "gaussian", "radius": 1.5, "alpha": 3})"));
    EXPECT_EQ(g.render.filter.type, FilterType::Gaussian);
    EXPECT_EQ(g.render.filter.radius, 1.5);
    EXPECT_EQ(g.render.filter.alpha, 3);
    EXPECT_EQ(loadSceneText(scene(R"({"type": "box"})")).render.filter.type, FilterType::Box);
    const struct {
        const char* filter;
        const char* pointer;
    } bad[] = {{R"("lanczos")", "/render/filter"},
               {R"(2)", "/render/filter"},
               {R"({"radius": 2})", "/render/filter/type"},
               {R"({"type": "sinc"})", "/render/filter/type"},
               {R"({"type": "mitchell", "radius": 0.25})", "/render/filter/radius"},
               {R"({"type": "mitchell", "radius": 9})", "/render/filter/radius"},
               {R"({"type": "mitchell", "b": 1.5})", "/render/filter/b"},
               {R"({"type": "mitchell", "alpha": 2})", "/render/filter/alpha"},
               {R"({"type": "gaussian", "alpha": 0})", "/render/filter/alpha"},
               {R"({"type": "box", "radius": 1})", "/render/filter/radius"}};
    for (const auto& b : bad) {
        try {
            loadSceneText(scene(b.filter));
            ADD_FAILURE() << b.filter << " was accepted";
        } catch (const ConfigError& e) {
            EXPECT_EQ(e.pointer(), b.pointer) << b.filter << ": " << e.what();
        }
    }
}

std::string withFilter(const FilterSettings& f) {
    return "/render/filter=" + ReconstructionFilter(f).parameters().dump();
}

// Every sample is the same radiance (an emitter filling the view): every pixel, at the image's
// edges too, is exactly that through any filter (Σ w L / Σ w), with no variance.
TEST(SplattingFilm, AConstantImageStaysConstantThroughEveryFilter) {
    const std::string scene = R"({"render": {"resolution": [13, 9]},
        "integrator": {"type": "path"},
        "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0], "fov": 60},
        "shapes": [{"type": "quad", "corner": [-5, -5, 0], "edge_u": [10, 0, 0],
                    "edge_v": [0, 10, 0], "emission": {"radiance": [2, 3, 0.7]}}]})";
    for (const FilterSettings& settings : someFilters()) {
        Json doc = parseSceneText(scene, "constant");
        applyOverride(doc, withFilter(settings));
        const LoadedScene s = loadSceneJson(doc);
        const TestRender r = renderScene(s, 3, 5);
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 13; ++x) {
                const Rgb m = r.film.mean(x, y), v = r.film.varianceOfMean(x, y);
                EXPECT_NEAR(m.r, 2.0f, 2e-6f) << x << ", " << y;
                EXPECT_NEAR(m.g, 3.0f, 3e-6f) << x << ", " << y;
                EXPECT_NEAR(m.b, 0.7f, 1e-6f) << x << ", " << y;
                EXPECT_LT(v.g, 1e-10f) << x << ", " << y;
                EXPECT_EQ(r.film.sampleCount(x, y), 3u);
            }
    }
}

LoadedScene spheres(const FilterSettings& filter, int width, int height,
                    const std::string& integrator = R"({"type":"path_mis"})") {
    return loadSceneFile("cornell_spheres.json", {"/render/resolution=[" + std::to_string(width) +
                                                      "," + std::to_string(height) + "]",
                                                  withFilter(filter), "/integrator=" + integrator});
}

void expectSameImage(const Film& a, const Film& b, const std::string& what) {
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            ASSERT_EQ(a.sampleCount(x, y), b.sampleCount(x, y)) << what;
            ASSERT_EQ(a.mean(x, y), b.mean(x, y)) << what << " at " << x << ", " << y;
            ASSERT_EQ(a.varianceOfMean(x, y), b.varianceOfMean(x, y)) << what;
        }
}

// Splats cross tile boundaries; the tiles are added in a fixed order, so one, two and four
// threads give the same bits.
TEST(SplattingFilm, TheImageIsIdenticalForAnyThreadCount) {
    for (const FilterSettings& f : {mitchell(), gaussian(2.6, 1)}) {
        const LoadedScene scene = spheres(f, 45, 37);
        const TestRender one = renderScene(scene, 9, 4, 1);
        const TestRender two = renderScene(scene, 9, 4, 2);
        const TestRender four = renderScene(scene, 9, 4, 4);
        expectSameImage(one.film, two.film, "one and two threads");
        expectSameImage(one.film, four.film, "one and four threads");
    }
}

// A splatting film's passes follow a plan fixed by the settings: a render stopped by a time
// limit after reaching n spp holds the bits of the fixed render of n spp.
TEST(SplattingFilm, ATimeLimitedImageIsTheFixedSppImageOfItsSpp) {
    const LoadedScene scene = spheres(mitchell(), 48, 40);
    Film timed(48, 40, scene.filmFilter());
    RenderOptions options;
    options.seed = 9;
    options.timeLimit = 0.3;
    options.sampler = scene.render.sampler;
    options.samplerSetSize = kMaxSpp;
    const std::unique_ptr<RenderSchedule> schedule =
        scene.schedule(scene.scheduleInputs(kMaxSpp, options.timeLimit));
    const RenderStats stats = render(*schedule, options, timed);
    ASSERT_TRUE(stats.complete);
    ASSERT_GT(stats.spp, 3u) << "too few passes to test the plan";
    std::printf("the time limit stopped at %u spp\n", stats.spp);
    Film fixed(48, 40, scene.filmFilter());
    options.timeLimit = 0;
    render(*scene.schedule(scene.scheduleInputs(stats.spp, 0)), options, fixed);
    expectSameImage(timed, fixed, "time-limited and fixed spp");
}

// The fixed plan: 1, 2, 4, … samples per pixel, at most 2^20 / pixels, the last cut to what is
// left of the spp; a time limit can only cut the last pass short.
TEST(SplattingFilm, ThePassPlanIsFixed) {
    const LoadedScene scene = spheres(mitchell(), 256, 256);  // at most 16 spp per pass
    const auto& integrator = dynamic_cast<const SampleIntegrator&>(*scene.integrator);
    auto passes = [&](uint32_t spp, double timeLimit, RoundTiming timing) {
        UniformPasses plan(*scene.scene, integrator, 256, 256, spp, timeLimit, true);
        std::vector<uint32_t> sizes;
        Round round;
        std::vector<PixelVisit> visits;
        const Film film(256, 256);
        while (plan.nextRound(film, timing, &round)) {
            plan.unitVisits(0, &visits);
            sizes.push_back(visits.front().count);
            timing.elapsed += timing.lastRoundSeconds;
        }
        return sizes;
    };
    // Whatever the rounds take.
    for (double seconds : {1e-6, 10.0})
        EXPECT_EQ(passes(100, 0, RoundTiming{0, 0, seconds, 0}),
                  (std::vector<uint32_t>{1, 2, 4, 8, 16, 16, 16, 16, 16, 5}));
    // 1/8 s per pass of any size, 7/16 s allowed: after 1 and 2 spp (1/4 s), 3 more fit of
    // the 4 planned; that pass is cut short and is the last (another would still fit 1 spp).
    EXPECT_EQ(passes(0, 0.4375, RoundTiming{0, 0.4375, 0.125, 0}),
              (std::vector<uint32_t>{1, 2, 3}));
}

// Splats land where the filter says, across tiles and rounds: synthetic samples splatted by
// three units whose tiles overlap, over two rounds, give every pixel the brute-force
// Σ w L / Σ w over all samples, and its variance.
TEST(SplattingFilm, EveryPixelIsTheSumOverTheSamplesWithinReach) {
    constexpr int kW = 37, kH = 23;
    for (const FilterSettings& settings : {mitchell(), mitchell(1.5), gaussian(2.6, 1)}) {
        const ReconstructionFilter filter(settings);
        Film film(kW, kH, filter);
        struct Sample {
            int x, y;
            Vec2 offset;
            Rgb value;
        };
        std::vector<Sample> all;
        const int edges[] = {0, 12, 25, kW};  // the units' columns
        for (uint32_t round = 0; round < 2; ++round) {
            film.beginRound(3);
            for (size_t unit = 0; unit < 3; ++unit) {
                SplatTile& tile = film.openTile(unit, edges[unit], 0, edges[unit + 1], kH);
                for (int y = 0; y < kH; ++y)
                    for (int x = edges[unit]; x < edges[unit + 1]; ++x)
                        for (uint32_t s = 0; s < 3; ++s) {
                            const uint64_t h = hashKeys(round, uint64_t(y * kW + x), s);
                            const Sample sample{
                                x, y,
                                Vec2(toUnitFloat(uint32_t(h)), toUnitFloat(uint32_t(h >> 32))),
                                Rgb(float(h % 97) / 10.0f, float(h % 13), 0.5f)};
                            tile.add(filter, x, y, sample.offset, sample.value);
                            film.countSample(x, y);
                            all.push_back(sample);
                        }
            }
            film.endRound();
        }
        for (int ty = 0; ty < kH; ++ty)
            for (int tx = 0; tx < kW; ++tx) {
                SplatSums sums;
                for (const Sample& s : all)
                    sums.add(filter.weight1D(double(s.x) + s.offset.x - tx - 0.5) *
                                 filter.weight1D(double(s.y) + s.offset.y - ty - 0.5),
                             s.value);
                const Rgb expected = sums.estimate(), variance = sums.varianceOfEstimate();
                const Rgb m = film.mean(tx, ty), v = film.varianceOfMean(tx, ty);
                for (int c = 0; c < 3; ++c) {
                    EXPECT_NEAR(m[c], expected[c], 1e-5f * (1 + std::abs(expected[c])))
                        << filterName(settings.type) << " at " << tx << ", " << ty;
                    EXPECT_NEAR(v[c], variance[c], 1e-4f * (1 + variance[c])) << tx << ", " << ty;
                }
                EXPECT_EQ(film.sampleCount(tx, ty), 6u);
            }
    }
}

// The ratio of the variance channel, averaged over the pixels, to the pixels' spread over seeds.
double varianceChannelOverSpread(const LoadedScene& scene) {
    constexpr int kSeeds = 200;
    const int w = scene.render.width, h = scene.render.height;
    std::vector<double> sum(size_t(w) * h, 0), squares(sum.size(), 0), predicted(sum.size(), 0);
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
        const TestRender r = renderScene(scene, 8, seed + 1);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double v = r.film.mean(x, y).g;
                sum[size_t(y) * w + x] += v;
                squares[size_t(y) * w + x] += v * v;
                predicted[size_t(y) * w + x] += r.film.varianceOfMean(x, y).g / kSeeds;
            }
    }
    double empirical = 0, channel = 0;
    for (size_t k = 0; k < sum.size(); ++k) {
        const double m = sum[k] / kSeeds;
        empirical += (squares[k] - kSeeds * m * m) / (kSeeds - 1);
        channel += predicted[k];
    }
    return channel / empirical;
}

// The variance channel (the linearised variance of Σ w L / Σ w, Kish-corrected) predicts the
// spread of the pixel over seeds. Where the image is flat and only the samples' own noise
// varies (a diffuse plane under a constant environment, lit by MIS), the ratio of the two,
// averaged over pixels, is near one for every filter: each pixel's spread is a χ² of 199
// degrees of freedom (relative s.e. 0.10); pixels within a filter's support share samples, so
// the 480 pixels are about 30 independent ones (480 / 16), which leaves a relative s.e. near
// 0.02: ±10 % is 5 of them, and room for the delta method's own O(1/n) error at 8 spp. Where the
// image varies within the filter's support the channel overestimates: it treats the samples as
// spread independently over the support, while each pixel gets its own 8 (stratified by pixel): on
// the Cornell spheres it must not underestimate.
TEST(SplattingFilm, TheVarianceChannelPredictsTheSpreadOverSeeds) {
    const std::string plane = R"({"render": {"resolution": [24, 20]},
        "integrator": {"type": "direct"},
        "camera": {"position": [0, 0, 1], "look_at": [0, 0, 0], "fov": 40},
        "shapes": [{"type": "quad", "corner": [-5, -5, 0], "edge_u": [10, 0, 0],
                    "edge_v": [0, 10, 0], "material": {"type": "lambert", "albedo": 0.5}}],
        "lights": [{"type": "environment", "radiance": 1}]})";
    for (const FilterSettings& f : {FilterSettings{}, mitchell(), gaussian()}) {
        Json doc = parseSceneText(plane, "plane");
        applyOverride(doc, withFilter(f));
        const double flat = varianceChannelOverSpread(loadSceneJson(doc));
        const double spheresRatio =
            varianceChannelOverSpread(spheres(f, 24, 20, R"({"type":"direct"})"));
        std::printf("%s: variance channel / spread over seeds: flat plane %.3f, spheres %.3f\n",
                    filterName(f.type), flat, spheresRatio);
        EXPECT_GT(flat, 0.9);
        EXPECT_LT(flat, 1.1);
        EXPECT_GT(spheresRatio, 0.9);
    }
}

// The filtered image's expectation is the long render's through the same filter: for the image
// and each 4 × 4 block (single pixels of a shadow are heavy-tailed: a rare splat from a lit
// neighbour), the mean over seeds against a long render, a t statistic with the long render's
// error included (its variance is the seeds' mean's scaled by their samples over its own),
// Šidák-corrected over blocks and channels. Negative control: the same renders against a box
// reference must be rejected (the filter blurs edges across blocks).
TEST(SplattingFilm, TheMeanOfAFilteredImageIsTheFilteredLongRender) {
    constexpr int kW = 24, kH = 20, kBlock = 4, kSeeds = 96;
    constexpr uint32_t kSpp = 16, kReferenceSpp = 16384;
    constexpr int kBlocks = (kW / kBlock) * (kH / kBlock) + 1;
    const int tests = kBlocks * 3 * 3;  // two filters and the negative control
    const double threshold = tThreshold(sidakAlpha(0.01, tests), kSeeds - 1);
    struct Block {
        int x0, y0, x1, y1;
    };
    std::vector<Block> blocks{{0, 0, kW, kH}};
    for (int y = 0; y < kH; y += kBlock)
        for (int x = 0; x < kW; x += kBlock)
            blocks.push_back({x, y, x + kBlock, y + kBlock});
    auto blockMean = [](const Film& film, const Block& b, int c) {
        double sum = 0;
        for (int y = b.y0; y < b.y1; ++y)
            for (int x = b.x0; x < b.x1; ++x)
                sum += film.mean(x, y)[c];
        return sum / double((b.x1 - b.x0) * (b.y1 - b.y0));
    };
    auto largestT = [&](const LoadedScene& scene, const Film& reference) {
        std::vector<double> sum(blocks.size() * 3, 0), squares(blocks.size() * 3, 0);
        for (uint32_t seed = 0; seed < kSeeds; ++seed) {
            const TestRender r = renderScene(scene, kSpp, seed + 1);
            for (size_t b = 0; b < blocks.size(); ++b)
                for (int c = 0; c < 3; ++c) {
                    const double v = blockMean(r.film, blocks[b], c);
                    sum[b * 3 + c] += v;
                    squares[b * 3 + c] += v * v;
                }
        }
        double worst = 0;
        for (size_t b = 0; b < blocks.size(); ++b)
            for (int c = 0; c < 3; ++c) {
                const size_t k = b * 3 + c;
                const double m = sum[k] / kSeeds;
                const double seedsVariance =
                    std::max(0.0, squares[k] - kSeeds * m * m) / (kSeeds - 1) / kSeeds;
                const double referenceVariance =
                    seedsVariance * double(kSeeds) * kSpp / double(kReferenceSpp);
                const double se = std::sqrt(seedsVariance + referenceVariance);
                const double r = blockMean(reference, blocks[b], c);
                if (se > 0) worst = std::max(worst, std::abs(m - r) / se);
            }
        return worst;
    };
    const std::string direct = R"({"type":"direct"})";
    for (const FilterSettings& f : {mitchell(), gaussian()}) {
        const LoadedScene scene = spheres(f, kW, kH, direct);
        const TestRender reference = renderScene(scene, kReferenceSpp, 1000);
        const double t = largestT(scene, reference.film);
        std::printf("%s: largest |t| %.2f (threshold %.2f)\n", filterName(f.type), t, threshold);
        EXPECT_LT(t, threshold);
        if (f.type == FilterType::Mitchell) {
            const TestRender box =
                renderScene(spheres(FilterSettings{}, kW, kH, direct), kReferenceSpp, 1000);
            const double control = largestT(scene, box.film);
            std::printf("against the box reference: largest |t| %.2f\n", control);
            EXPECT_GT(control, threshold);
        }
    }
}

}  // namespace
}  // namespace rr::test
