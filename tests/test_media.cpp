// Participating media: free-flight distance sampling and phase-function sampling against their
// densities (χ²), transmittance and normalisation in closed form, the estimators' expected
// weights, and scenes with known answers rendered by `path` and `path_mis` (z-tests against the
// per-pixel variance): absorption through a slab and a sphere of fog, radiance conservation by
// scattering-only fog in a uniform emitter, infinite lights behind an infinite medium, and the
// two integrators agreeing on a foggy scene. Scenes without media must not change at all.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "math/frame.h"
#include "scene/media/henyey_greenstein.h"
#include "scene/media/homogeneous_medium.h"
#include "scene/media/isotropic_phase.h"
#include "support/chi2.h"
#include "support/histograms.h"
#include "support/scene_testing.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

// Every χ² run in this file: free flight (grey, chromatic, chromatic with a transparent
// channel to infinity, a chain of three segments) 4, HG at four g and isotropic 5, negative
// controls 2.
constexpr int kRuns = 11;
const Chi2Family kChi2(kRuns);
constexpr int kSamples = 1000000;

// Every z-test in this file (Šidák, family-wise 0.01): expected weights 2 media × 3 channels,
// HG mean cosine 4, seven analytic scenes × 2 integrators and two point-light scenes × 1
// integrator, each 3 channel means + 16 blocks, and the path/path_mis agreement (3 + 16).
constexpr int kZTests = 6 + 4 + (7 * 2 + 2) * 19 + 19;
const double kZ = zThreshold(sidakAlpha(0.01, kZTests));

constexpr float kInfinity = std::numeric_limits<float>::infinity();

std::unique_ptr<HomogeneousMedium> medium(const Rgb& sigmaA, const Rgb& sigmaS) {
    return std::make_unique<HomogeneousMedium>(sigmaA, sigmaS, std::make_unique<IsotropicPhase>());
}

// --- Transmittance and the survival function -------------------------------------------------

// S(t) of the test, written independently of the medium's code: mean_c e^{−σc t}.
double survivalOf(const Rgb& sigmaT, double t) {
    double sum = 0;
    for (int c = 0; c < 3; ++c)
        sum += sigmaT[c] > 0 ? std::exp(-sigmaT[c] * t) : 1.0;
    return sum / 3;
}

TEST(HomogeneousMedium, TransmittanceIsExponentialInEveryChannel) {
    const auto m = medium(Rgb(0.1f, 0, 2), Rgb(0.4f, 0, 1));
    const Rgb sigmaT(0.5f, 0, 3);
    for (float d : {0.0f, 0.01f, 0.7f, 3.0f, 10.0f}) {
        const Rgb tr = m->transmittance(d);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(tr[c], std::exp(-double(sigmaT[c]) * d), 1e-6 * std::exp(-sigmaT[c] * d))
                << "d = " << d << ", channel " << c;
        EXPECT_NEAR(m->survival(d), survivalOf(sigmaT, d), 1e-7);
    }
    // Infinitely far: nothing gets through but the transparent channel.
    EXPECT_EQ(m->transmittance(kInfinity), Rgb(0, 1, 0));
    EXPECT_NEAR(m->survival(kInfinity), 1.0 / 3, 1e-7);
}

// The distance map inverts S to float precision, even for σt spanning four decades, and the
// density is −S'.
TEST(HomogeneousMedium, DistanceMapInvertsTheSurvivalFunction) {
    for (const Rgb sigmaA : {Rgb(0.01f, 1, 100), Rgb(1.3f), Rgb(0, 0.5f, 2)}) {
        const auto m = medium(sigmaA, Rgb(0.0f));
        const double floor = survivalOf(sigmaA, kInfinity);
        for (int i = 0; i < 2000; ++i) {
            const float v = float(floor + (1 - floor) * (i + 0.5) / 2000);
            const float t = m->distanceForSurvival(v);
            ASSERT_NEAR(survivalOf(sigmaA, t), v, 2e-6 * v) << "v = " << v;
            const double h = 1e-3 * std::max(t, 1e-3f);
            const double derivative =
                (survivalOf(sigmaA, t - h) - survivalOf(sigmaA, t + h)) / (2 * h);
            if (t > h) {
                ASSERT_NEAR(m->distancePdf(t), derivative, 1e-3 * derivative) << t;
            }
        }
    }
}

// --- Free-flight χ² ------------------------------------------------------------------------------

// A ray through consecutive homogeneous segments; the flight's budget carries from one to the
// next as in the path tracer. Cells: `cells` equal cells of distance per finite segment, or over
// [0, tailStart) plus a tail cell for an infinite one; then one cell for "no collision".
struct Segment {
    const HomogeneousMedium* medium;
    float length;  // may be infinite (last segment only)
};

struct FlightCells {
    std::vector<double> observed, expected;
};

FlightCells freeFlightHistogram(const std::vector<Segment>& segments, int cells, float tailStart,
                                uint64_t seed, const std::vector<Rgb>& claimedSigmaT = {}) {
    const int perSegment = cells + 1;  // the tail cell exists only for an infinite segment
    FlightCells h;
    h.observed.assign(segments.size() * perSegment + 1, 0);
    h.expected.assign(h.observed.size(), 0);
    auto cellOf = [&](size_t k, float t) {
        const float width = (std::isinf(segments[k].length) ? tailStart : segments[k].length);
        const int i = int(t / width * cells);
        return k * perSegment + std::min(i, std::isinf(segments[k].length) ? cells : cells - 1);
    };
    for (int n = 0; n < kSamples; ++n) {
        float budget = 1.0f - uniform(seed, n);
        bool collided = false;
        for (size_t k = 0; k < segments.size() && !collided; ++k) {
            const FreeFlight f = segments[k].medium->sampleFreeFlight(budget, segments[k].length);
            if (f.collided) {
                h.observed[cellOf(k, f.distance)] += 1;
                collided = true;
            }
            budget = f.budgetLeft;
        }
        if (!collided) h.observed.back() += 1;
    }
    // Expected: the probability of reaching segment k times S_k(a) − S_k(b) for each cell.
    double reach = 1;
    for (size_t k = 0; k < segments.size(); ++k) {
        const Rgb sigmaT = claimedSigmaT.empty() ? segments[k].medium->sigmaT() : claimedSigmaT[k];
        const bool infinite = std::isinf(segments[k].length);
        const double width = infinite ? tailStart : segments[k].length;
        for (int i = 0; i < cells; ++i)
            h.expected[k * perSegment + i] = kSamples * reach *
                                             (survivalOf(sigmaT, width * i / cells) -
                                              survivalOf(sigmaT, width * (i + 1) / cells));
        if (infinite)
            h.expected[k * perSegment + cells] =
                kSamples * reach * (survivalOf(sigmaT, width) - survivalOf(sigmaT, kInfinity));
        reach *= survivalOf(sigmaT, segments[k].length);
    }
    h.expected.back() = kSamples * reach;
    return h;
}

Chi2Outcome freeFlightChi2(const std::vector<Segment>& segments, int cells, float tailStart,
                           uint64_t seed) {
    const FlightCells h = freeFlightHistogram(segments, cells, tailStart, seed);
    return chi2GoodnessOfFit(h.observed, h.expected);
}

TEST(FreeFlight, GreyDistancesFollowTheExponentialWithSurfaceCell) {
    const auto m = medium(Rgb(0.3f), Rgb(1.0f));
    kChi2.expectFits(freeFlightChi2({{m.get(), 2.5f}}, 50, 0, 11));
}

TEST(FreeFlight, ChromaticDistancesFollowTheChannelMixture) {
    const auto m = medium(Rgb(0.1f, 0.5f, 3), Rgb(0.4f, 1.5f, 5));
    kChi2.expectFits(freeFlightChi2({{m.get(), 1.5f}}, 60, 0, 12));
}

// σt = 0 in one channel: a third of the flights never collide, even on an infinite ray.
TEST(FreeFlight, TransparentChannelEscapesToInfinityWithItsShare) {
    const auto m = medium(Rgb(0, 0.5f, 1), Rgb(0, 0.5f, 2));
    kChi2.expectFits(freeFlightChi2({{m.get(), kInfinity}}, 60, 6.0f, 13));
}

// Across boundaries the budget left by one segment drives the next: the distance along the
// whole ray must follow the product of the segments' survival functions.
TEST(FreeFlight, BudgetCarriesAcrossSegments) {
    const auto a = medium(Rgb(0.1f, 0.5f, 3), Rgb(0.4f, 1.5f, 5));
    const auto b = medium(Rgb(0.2f), Rgb(1.3f));
    kChi2.expectFits(
        freeFlightChi2({{a.get(), 0.4f}, {b.get(), 1.0f}, {a.get(), kInfinity}}, 40, 2.0f, 14));
}

// Negative control: chromatic samples judged by the grey exponential of the mean σt.
TEST(FreeFlightNegativeControl, ChromaticSamplesRejectGreyDensityOfMeanSigma) {
    const auto m = medium(Rgb(0.1f, 0.5f, 3), Rgb(0.4f, 1.5f, 5));
    const FlightCells h = freeFlightHistogram({{m.get(), 1.5f}}, 60, 0, 15, {Rgb(3.5f)});
    kChi2.expectRejects(chi2GoodnessOfFit(h.observed, h.expected));
}

// The weights make the estimator unbiased: E[weight] = ∫₀^tMax Tr σs dt + Tr(tMax)
// = σs/σt (1 − e^{−σt tMax}) + e^{−σt tMax} per channel.
TEST(FreeFlight, ExpectedWeightIsAlbedoIntegralPlusTransmittance) {
    const Rgb sigmaA(0.3f, 0.5f, 5), sigmaS(0.2f, 1.5f, 3);
    const auto m = medium(sigmaA, sigmaS);
    for (const float tMax : {1.2f, kInfinity}) {
        constexpr int n = 200000;
        double sum[3] = {0, 0, 0}, sumSquares[3] = {0, 0, 0};
        for (int i = 0; i < n; ++i) {
            const Rgb w = m->sampleFreeFlight(1.0f - uniform(21, i), tMax).weight;
            for (int c = 0; c < 3; ++c) {
                sum[c] += w[c];
                sumSquares[c] += double(w[c]) * w[c];
            }
        }
        for (int c = 0; c < 3; ++c) {
            const double sigmaT = sigmaA[c] + sigmaS[c], tr = std::exp(-sigmaT * tMax);
            const double expected = sigmaS[c] / sigmaT * (1 - tr) + tr;
            const double mean = sum[c] / n;
            const double se = std::sqrt((sumSquares[c] / n - mean * mean) / (n - 1));
            EXPECT_LE(std::abs(mean - expected), kZ * se)
                << "tMax " << tMax << " channel " << c << ": " << mean << " ± " << se
                << ", expected " << expected;
        }
    }
}

// --- Phase functions -----------------------------------------------------------------------------

const Vec3 kWo = normalize(Vec3(0.3f, -0.5f, 0.8f));

// Histogram of sampled directions in a cap of `capDegrees` around `axis` (180: the sphere),
// like the BSDF checks, plus consistency of the returned pdf with pdf() and eval().
Chi2Outcome phaseChi2(const PhaseFunction& sampled, const PhaseFunction& claimed, const Vec3& axis,
                      double capDegrees, uint64_t seed) {
    const Frame cap(normalize(axis));
    const double zMin = std::max(-1.0, std::cos(capDegrees * M_PI / 180));
    DirectionHistogram histogram(41, 60, zMin);
    int mismatches = 0;
    for (int i = 0; i < kSamples; ++i) {
        Vec3 wi;
        const float pdf = sampled.sample(kWo, uniform2(seed, i), &wi);
        const float check = sampled.pdf(kWo, wi);
        mismatches += !(std::abs(pdf - check) <= 1e-4f * check) || sampled.eval(kWo, wi) != check ||
                      std::abs(length(wi) - 1) > 1e-5f;
        histogram.add(cap.toLocal(wi));
    }
    EXPECT_EQ(mismatches, 0) << "returned pdf, pdf() and eval() must agree; directions unit";
    std::vector<double> expected = histogram.expected(
        [&](const Vec3& w) { return double(claimed.pdf(kWo, cap.toWorld(w))); }, kSamples);
    double inside = 0;
    for (size_t i = 0; i + 1 < expected.size(); ++i)
        inside += expected[i];
    expected.back() = zMin > -1 ? std::max(0.0, kSamples - inside) : 0.0;
    return chi2GoodnessOfFit(histogram.counts(), expected);
}

class HenyeyGreensteinSampling : public ::testing::TestWithParam<float> {};

// Strongly peaked lobes are zoomed: a 40° cap around the peak (forward −wo for g > 0, backward
// wo for g < 0), the rest of the sphere one cell. Other g: the whole sphere, in a frame not
// aligned with the lobe.
TEST_P(HenyeyGreensteinSampling, DirectionsFollowPdf) {
    const float g = GetParam();
    const HenyeyGreenstein hg(g);
    const bool zoom = std::abs(g) >= 0.9f;
    const Vec3 axis = zoom ? (g > 0 ? -kWo : kWo) : Vec3(0, 0, 1);
    kChi2.expectFits(phaseChi2(hg, hg, axis, zoom ? 40 : 180, 31 + uint64_t(10 * (g + 1))),
                     "HG g = " + std::to_string(g));
}

// The sign convention: g is the mean cosine of the scattering angle, cos θ = −dot(wo, wi).
TEST_P(HenyeyGreensteinSampling, MeanCosineIsG) {
    const float g = GetParam();
    const HenyeyGreenstein hg(g);
    constexpr int n = 200000;
    double sum = 0, sumSquares = 0;
    for (int i = 0; i < n; ++i) {
        Vec3 wi;
        hg.sample(kWo, uniform2(41, i), &wi);
        const double c = -dot(kWo, wi);
        sum += c;
        sumSquares += c * c;
    }
    const double mean = sum / n, se = std::sqrt((sumSquares / n - mean * mean) / (n - 1));
    EXPECT_LE(std::abs(mean - g), kZ * se) << mean << " ± " << se;
}

// ∫ p dω = 1 by midpoint quadrature over the sphere in a frame not aligned with the lobe.
TEST_P(HenyeyGreensteinSampling, IntegratesToOne) {
    const HenyeyGreenstein hg(GetParam());
    constexpr int nz = 4000, nphi = 2000;
    double sum = 0;
    for (int i = 0; i < nz; ++i) {
        const double z = -1 + (i + 0.5) * 2.0 / nz, r = std::sqrt(1 - z * z);
        for (int j = 0; j < nphi; ++j) {
            const double phi = (j + 0.5) * 2 * M_PI / nphi;
            sum += hg.eval(kWo, Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
        }
    }
    EXPECT_NEAR(sum * (2.0 / nz) * (2 * M_PI / nphi), 1.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(G, HenyeyGreensteinSampling, ::testing::Values(-0.9f, 0.0f, 0.3f, 0.9f),
                         [](const auto& param) {
                             const int hundredths = int(std::lround(param.param * 100));
                             return (hundredths < 0 ? "minus_" : "plus_") +
                                    std::to_string(std::abs(hundredths));
                         });

TEST(IsotropicPhase, DirectionsAreUniformAndIntegrateToOne) {
    const IsotropicPhase iso;
    kChi2.expectFits(phaseChi2(iso, iso, Vec3(0, 0, 1), 180, 51));
    EXPECT_NEAR(iso.eval(kWo, Vec3(0, 0, 1)) * 4 * M_PI, 1.0, 1e-6);
}

// Negative control: g = 0.3 samples judged by the g = −0.3 density (a flipped sign convention).
TEST(PhaseChi2NegativeControl, ForwardSamplesRejectBackwardDensity) {
    kChi2.expectRejects(
        phaseChi2(HenyeyGreenstein(0.3f), HenyeyGreenstein(-0.3f), Vec3(0, 0, 1), 180, 52));
}

// --- Scenes with known answers -------------------------------------------------------------------

// Expected pixel values by quadrature over each pixel's footprint: `radiance(ray)` is the
// closed-form value along a camera ray.
Film pixelQuadrature(const Scene& scene, const std::function<Rgb(const Ray&)>& radiance,
                     int kSub = 12) {
    const Camera& camera = scene.camera();
    Film expected(camera.width(), camera.height());
    for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
            double sum[3] = {0, 0, 0};
            for (int a = 0; a < kSub; ++a)
                for (int b = 0; b < kSub; ++b) {
                    const Rgb l = radiance(inFileSpace(
                        scene,
                        camera.generateRay(Vec2(x + (a + 0.5f) / kSub, y + (b + 0.5f) / kSub),
                                           Vec2(0.5f, 0.5f), 0)));
                    for (int c = 0; c < 3; ++c)
                        sum[c] += l[c];
                }
            expected.add(x, y,
                         Rgb(float(sum[0]), float(sum[1]), float(sum[2])) / float(kSub * kSub));
        }
    return expected;
}

Film constantFilm(const Scene& scene, const Rgb& value) {
    return pixelQuadrature(scene, [&](const Ray&) { return value; });
}

// The image mean of each channel and the mean of channel 0 over each of 4×4 blocks, z-tested
// against `expected` (1e-4 relative slack for the quadrature).
void expectImageMatches(const Film& film, const Film& expected, const std::string& what) {
    auto check = [&](int c, int x0, int y0, int x1, int y1, const std::string& where) {
        const Estimate got = regionMean(film, c, x0, y0, x1, y1);
        const double want = regionMean(expected, c, x0, y0, x1, y1).mean;
        EXPECT_LE(std::abs(got.mean - want), kZ * got.standardError + 1e-4 * want)
            << what << " " << where << ": " << got.mean << " ± " << got.standardError
            << ", expected " << want;
    };
    for (int c = 0; c < 3; ++c)
        check(c, 0, 0, film.width(), film.height(), "channel " + std::to_string(c));
    const int bw = film.width() / 4, bh = film.height() / 4;
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx)
            check(0, bx * bw, by * bh, (bx + 1) * bw, (by + 1) * bh,
                  "block " + std::to_string(bx) + "," + std::to_string(by));
}

class MediaScenes : public ::testing::TestWithParam<std::string> {
  protected:
    std::string header() const {
        return R"({"render": {"resolution": [16, 16], "max_depth": -1, "rr_depth": 1},
                   "integrator": {"type": ")" +
               GetParam() + R"("},)";
    }
};

// A camera looking through an absorbing medium filling the scene at an emitter: every ray
// sees L·e^{−σa d}, d the distance to the emitter plane z = −1.
TEST_P(MediaScenes, AbsorbingSceneMediumAttenuatesAnEmitter) {
    const LoadedScene scene = loadSceneText(header() + R"(
        "medium": {"sigma_a": [0.2, 0.5, 1.0]},
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 50},
        "shapes": [{"type": "quad", "corner": [-10, -10, -1], "edge_u": [20, 0, 0],
                    "edge_v": [0, 20, 0], "emission": {"radiance": [2, 3, 4]}}]})");
    ASSERT_TRUE(scene.scene->hasMedia());
    const TestRender r = renderScene(scene, 256);
    const Film expected = pixelQuadrature(*scene.scene, [](const Ray& ray) {
        const double d = (ray.origin.z + 1) / -ray.direction.z;
        return Rgb(float(2 * std::exp(-0.2 * d)), float(3 * std::exp(-0.5 * d)),
                   float(4 * std::exp(-1.0 * d)));
    });
    expectImageMatches(r.film, expected, "absorbing scene medium");
}

// The same through a sphere of absorbing fog with no material (an index-matched boundary):
// L·e^{−σa chord}. Every camera ray crosses the sphere (chord ≥ 1.2).
TEST_P(MediaScenes, AbsorbingFogSphereAttenuatesByItsChord) {
    const LoadedScene scene = loadSceneText(header() + R"(
        "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "fov": 16},
        "shapes": [
          {"type": "sphere", "radius": 1, "interior_medium": {"sigma_a": [0.7, 1.2, 2.0]}},
          {"type": "quad", "corner": [-10, -10, -2], "edge_u": [20, 0, 0], "edge_v": [0, 20, 0],
           "emission": {"radiance": [2, 3, 4]}}]})");
    const TestRender r = renderScene(scene, 256);
    const Film expected = pixelQuadrature(*scene.scene, [](const Ray& ray) {
        const double b = dot(ray.origin, ray.direction);
        const double chord = 2 * std::sqrt(std::max(0.0, b * b - (lengthSquared(ray.origin) - 1)));
        return Rgb(float(2 * std::exp(-0.7 * chord)), float(3 * std::exp(-1.2 * chord)),
                   float(4 * std::exp(-2.0 * chord)));
    });
    expectImageMatches(r.film, expected, "absorbing fog sphere");
}

// Scattering without absorption conserves radiance in a uniform radiance field: inside a
// uniform emitter every pixel is exactly Le, whatever the fog. Chromatic σs and a forward HG
// lobe exercise the channel-mixture distance sampling and the phase sampling.
TEST_P(MediaScenes, ScatteringFogSphereInUniformEmitterRendersLe) {
    const LoadedScene scene = loadSceneText(header() + R"(
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 20},
        "shapes": [
          {"type": "sphere", "radius": 10, "emission": {"radiance": [1.5, 1, 0.5], "two_sided": true}},
          {"type": "sphere", "radius": 1,
           "interior_medium": {"sigma_s": [1, 2, 4],
                               "phase": {"type": "henyey_greenstein", "g": 0.6}}}]})");
    const TestRender r = renderScene(scene, 128);
    expectImageMatches(r.film, constantFilm(*scene.scene, Rgb(1.5f, 1, 0.5f)),
                       "scattering fog sphere in a uniform emitter");
}

// The same under a constant environment light: escaping rays and next-event estimation to an
// infinite light through the fog.
TEST_P(MediaScenes, ScatteringFogSphereUnderConstantEnvironmentRendersLe) {
    const LoadedScene scene = loadSceneText(header() + R"(
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 20},
        "shapes": [{"type": "sphere", "radius": 1, "interior_medium": {"sigma_s": 2.5}}],
        "lights": [{"type": "environment", "radiance": [1.5, 1, 0.5]}]})");
    const TestRender r = renderScene(scene, 128);
    expectImageMatches(r.film, constantFilm(*scene.scene, Rgb(1.5f, 1, 0.5f)),
                       "scattering fog sphere under an environment");
}

// A scattering scene medium, backward HG, inside a uniform emitter: the camera is in the fog.
TEST_P(MediaScenes, ScatteringSceneMediumInUniformEmitterRendersLe) {
    const LoadedScene scene = loadSceneText(header() + R"(
        "medium": {"sigma_s": [0.3, 0.6, 0.9], "phase": {"type": "henyey_greenstein", "g": -0.4}},
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 60},
        "shapes": [{"type": "sphere", "radius": 5,
                    "emission": {"radiance": [1.5, 1, 0.5], "two_sided": true}}]})");
    const TestRender r = renderScene(scene, 128);
    expectImageMatches(r.film, constantFilm(*scene.scene, Rgb(1.5f, 1, 0.5f)),
                       "scattering scene medium in a uniform emitter");
}

// Glass filled with scattering fog: the medium is entered and left by refraction, and
// radiance is still conserved.
TEST_P(MediaScenes, FogFilledGlassSphereInUniformEmitterRendersLe) {
    const LoadedScene scene = loadSceneText(header() + R"(
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 20},
        "shapes": [
          {"type": "sphere", "radius": 10, "emission": {"radiance": 1.5, "two_sided": true}},
          {"type": "sphere", "radius": 1, "material": {"type": "dielectric", "ior": 1.5},
           "interior_medium": {"sigma_s": 2}}]})");
    const TestRender r = renderScene(scene, 128);
    expectImageMatches(r.film, constantFilm(*scene.scene, Rgb(1.5f)),
                       "fog-filled glass sphere in a uniform emitter");
}

// The scene medium fills all space, so it extinguishes an environment light in every channel
// where σt > 0; a channel with σt = 0 sees the environment unattenuated, however the other
// channels scatter.
TEST_P(MediaScenes, SceneMediumExtinguishesInfiniteLightsExceptTransparentChannels) {
    const LoadedScene scene = loadSceneText(header() + R"(
        "medium": {"sigma_a": [0, 0.5, 0.5], "sigma_s": [0, 0.5, 1]},
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 40},
        "shapes": [],
        "lights": [{"type": "environment", "radiance": [1, 2, 3]}]})");
    const TestRender r = renderScene(scene, 128);
    expectImageMatches(r.film, constantFilm(*scene.scene, Rgb(1, 0, 0)),
                       "environment behind an infinite medium");
}

INSTANTIATE_TEST_SUITE_P(Integrators, MediaScenes, ::testing::Values("path", "path_mis"),
                         [](const auto& param) { return param.param; });

// Point lights are found by next-event estimation only: `path_mis` alone.

// A point light over a diffuse floor in an absorbing medium: the camera ray and the shadow
// ray are both attenuated, L = ρ/π · I cos θ / r² · e^{−σa (r + d)}, d the camera distance.
TEST(MediaPointLight, DiffuseFloorInAbsorbingFogMatchesClosedForm) {
    const LoadedScene scene = loadSceneText(R"({
        "render": {"resolution": [16, 16], "max_depth": 1},
        "integrator": {"type": "path_mis"},
        "medium": {"sigma_a": [0.1, 0.3, 0.6]},
        "camera": {"position": [0, 1, 2], "look_at": [0, 0, 0], "fov": 50},
        "shapes": [{"type": "quad", "corner": [-10, 0, 10], "edge_u": [20, 0, 0],
                    "edge_v": [0, 0, -20], "material": {"type": "lambert", "albedo": 0.6}}],
        "lights": [{"type": "point", "position": [0.3, 0.8, -0.2], "intensity": 5}]})");
    const TestRender r = renderScene(scene, 64);
    const Vec3 light(0.3f, 0.8f, -0.2f);
    const Film expected = pixelQuadrature(*scene.scene, [&](const Ray& ray) {
        const double t = -double(ray.origin.y) / ray.direction.y;
        const Vec3 p = ray.origin + ray.direction * float(t), d = light - p;
        const double dist = length(d), irradiance = 5.0 * (d.y / dist) / (dist * dist);
        auto channel = [&](double sigma) {
            return float(0.6 / M_PI * irradiance * std::exp(-sigma * (dist + t)));
        };
        return Rgb(channel(0.1), channel(0.3), channel(0.6));
    });
    expectImageMatches(r.film, expected, "point light over a floor in absorbing fog");
}

// Single scattering of a point light in a fog filling the scene (max_depth 1: one medium
// vertex, next-event estimation, nothing else), against the 1-D integral along each camera
// ray: L = ∫₀^∞ e^{−σt t} σs p(cos θ) I e^{−σt r} / r² dt, r the distance from x(t) to the light,
// cos θ = dot(ray direction, light − x)/r. The light is off screen, beside the view, where a
// forward lobe (g = 0.7) and its mirror image (g = −0.7) differ by a factor of ~4: the phase
// function's orientation at medium vertices is under test.
TEST(MediaPointLight, SingleScatteringMatchesQuadrature) {
    const LoadedScene scene = loadSceneText(R"({
        "render": {"resolution": [16, 16], "max_depth": 1},
        "integrator": {"type": "path_mis"},
        "medium": {"sigma_a": 0.05, "sigma_s": [0.3, 0.5, 0.8],
                   "phase": {"type": "henyey_greenstein", "g": 0.7}},
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1], "fov": 30},
        "shapes": [],
        "lights": [{"type": "point", "position": [2, 0.5, -3], "intensity": 5}]})");
    const TestRender r = renderScene(scene, 64);
    const Vec3 light(2, 0.5f, -3);
    const double sigmaS[3] = {0.3, 0.5, 0.8}, g = 0.7;
    const Film expected = pixelQuadrature(
        *scene.scene,
        [&](const Ray& ray) {
            // Simpson's rule on [0, 60]: e^{−0.35·60} < 1e-9; the light stays ≥ 0.8 away.
            constexpr int n = 4000;
            constexpr double length = 60, h = length / n;
            double sum[3] = {0, 0, 0};
            for (int i = 0; i <= n; ++i) {
                const double t = i * h, weight = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
                const Vec3 d = light - (ray.origin + ray.direction * float(t));
                const double dist = rr::length(d), cosTheta = dot(ray.direction, d) / dist;
                const double phase =
                    (1 - g * g) / (4 * M_PI * std::pow(1 + g * g - 2 * g * cosTheta, 1.5));
                for (int c = 0; c < 3; ++c)
                    sum[c] += weight * std::exp(-(sigmaS[c] + 0.05) * (t + dist)) * sigmaS[c] *
                              phase * 5.0 / (dist * dist);
            }
            return Rgb(float(sum[0]), float(sum[1]), float(sum[2])) * float(h / 3);
        },
        4);
    expectImageMatches(r.film, expected, "single scattering of a point light");
}

// A small foggy scene (fog everywhere, a denser fog sphere, a diffuse floor, a small spherical
// light): no closed form, but `path` and `path_mis` estimate the same thing, so they must
// agree within their errors (two-sample z-tests).
const char* kFoggyScene = R"({
    "render": {"resolution": [16, 16], "max_depth": 8, "rr_depth": 3},
    "medium": {"sigma_a": 0.05, "sigma_s": [0.2, 0.35, 0.5],
               "phase": {"type": "henyey_greenstein", "g": 0.3}},
    "camera": {"position": [0, 0.3, 3], "look_at": [0, -0.3, 0], "fov": 45},
    "shapes": [
      {"type": "quad", "corner": [-5, -1, 5], "edge_u": [10, 0, 0], "edge_v": [0, 0, -10],
       "material": {"type": "lambert", "albedo": 0.6}},
      {"type": "sphere", "center": [0.3, -0.2, 0], "radius": 0.5,
       "interior_medium": {"sigma_a": 0.2, "sigma_s": [2, 1, 0.5],
                           "phase": {"type": "henyey_greenstein", "g": -0.3}}},
      {"type": "sphere", "center": [-0.4, 0.6, -0.3], "radius": 0.15,
       "emission": {"radiance": 30}}]})";

TEST(MediaAgreement, PathAndPathMisAgreeOnAFoggyScene) {
    Json doc = parseSceneText(kFoggyScene, "foggy scene");
    doc["integrator"] = {{"type", "path"}};
    const TestRender path = renderScene(loadSceneJson(doc), 2048, 3);
    doc["integrator"] = {{"type", "path_mis"}};
    const TestRender mis = renderScene(loadSceneJson(doc), 256, 4);
    auto check = [&](int c, int x0, int y0, int x1, int y1, const std::string& where) {
        const Estimate a = regionMean(path.film, c, x0, y0, x1, y1);
        const Estimate b = regionMean(mis.film, c, x0, y0, x1, y1);
        const double se = std::hypot(a.standardError, b.standardError);
        EXPECT_LE(std::abs(a.mean - b.mean), kZ * se)
            << where << ": path " << a.mean << " ± " << a.standardError << ", path_mis " << b.mean
            << " ± " << b.standardError;
    };
    for (int c = 0; c < 3; ++c)
        check(c, 0, 0, 16, 16, "channel " + std::to_string(c));
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx)
            check(0, 4 * bx, 4 * by, 4 * bx + 4, 4 * by + 4,
                  "block " + std::to_string(bx) + "," + std::to_string(by));
}

// --- No cost, no change, determinism -------------------------------------------------------------

void expectIdentical(const Film& a, const Film& b) {
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            ASSERT_EQ(a.mean(x, y), b.mean(x, y)) << "pixel " << x << "," << y;
            ASSERT_EQ(a.varianceOfMean(x, y), b.varianceOfMean(x, y)) << "pixel " << x << "," << y;
        }
}

// A vacuum medium (σa = σs = 0) filling the scene and the glass sphere sends every path
// through the media code (free flights, shadow rays by transmittance) without changing any
// value: the image must be bit-identical to the scene without media.
TEST(MediaCost, VacuumMediaRenderBitIdenticallyToNoMedia) {
    const std::vector<std::string> base = {"/render/resolution=[24,24]"};
    std::vector<std::string> withMedia = base;
    withMedia.push_back(R"(/medium={"sigma_a": 0, "sigma_s": 0})");
    withMedia.push_back(R"(/shapes/7/interior_medium={"sigma_s": 0})");
    for (const std::string integrator : {"path", "path_mis"}) {
        SCOPED_TRACE(integrator);
        std::vector<std::string> plainOverrides = base, vacuumOverrides = withMedia;
        plainOverrides.push_back("/integrator/type=" + integrator);
        vacuumOverrides.push_back("/integrator/type=" + integrator);
        const LoadedScene plain = loadSceneFile("cornell_spheres.json", plainOverrides);
        const LoadedScene vacuum = loadSceneFile("cornell_spheres.json", vacuumOverrides);
        ASSERT_FALSE(plain.scene->hasMedia());
        ASSERT_TRUE(vacuum.scene->hasMedia());
        expectIdentical(renderScene(plain, 16, 5).film, renderScene(vacuum, 16, 5).film);
    }
}

TEST(MediaDeterminism, OneAndTwoThreadsGiveIdenticalPixels) {
    Json doc = parseSceneText(kFoggyScene, "foggy scene");
    doc["render"]["resolution"] = {50, 37};
    const LoadedScene scene = loadSceneJson(doc);
    const TestRender one = renderScene(scene, 8, 7, /*threads=*/1);
    const TestRender two = renderScene(scene, 8, 7, /*threads=*/2);
    expectIdentical(one.film, two.film);
    EXPECT_EQ(one.stats.rays.total(), two.stats.rays.total());
}

// --- Configuration errors ------------------------------------------------------------------------

const char* kMinimalScene = R"({
  "render": {"resolution": [8, 8], "spp": 1},
  "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0]},
  "shapes": [{"type": "sphere", "radius": 0.5, "emission": {"radiance": 1}},
             {"type": "sphere", "center": [2, 0, 0], "radius": 0.5, "material": {"type": "lambert"}}]
})";

std::string errorPointer(const std::vector<std::string>& overrides) {
    try {
        Json doc = parseSceneText(kMinimalScene, "test");
        for (const auto& o : overrides)
            applyOverride(doc, o);
        loadScene(doc, AssetResolver({}));
    } catch (const ConfigError& e) {
        return e.pointer();
    }
    return "<no error>";
}

TEST(MediaConfig, ValidMediaLoad) {
    EXPECT_EQ(errorPointer({R"(/medium={"sigma_a": 0.1, "sigma_s": [0.1, 0.2, 0.3],
                                         "phase": {"type": "henyey_greenstein", "g": -0.5}})",
                            R"(/shapes/1/interior_medium={"sigma_s": 1})"}),
              "<no error>");
    // A shape with an interior medium may omit its material: an index-matched boundary.
    EXPECT_EQ(errorPointer({R"(/shapes/1={"type": "sphere", "center": [2, 0, 0], "radius": 0.5,
                                          "interior_medium": {}})"}),
              "<no error>");
}

TEST(MediaConfig, BadValuesNameTheirPointer) {
    EXPECT_EQ(errorPointer({R"(/medium={"sigma_a": -0.1})"}), "/medium/sigma_a");
    EXPECT_EQ(errorPointer({R"(/medium={"sigma_s": [0, -1, 0]})"}), "/medium/sigma_s/1");
    EXPECT_EQ(errorPointer({R"(/medium={"density": 1})"}), "/medium/density");
    EXPECT_EQ(errorPointer({R"(/medium={"phase": {"type": "henyey_greenstein", "g": 1}})"}),
              "/medium/phase/g");
    EXPECT_EQ(errorPointer({R"(/medium={"phase": {"type": "henyey_greenstein", "g": -1.5}})"}),
              "/medium/phase/g");
    EXPECT_EQ(errorPointer({R"(/medium={"phase": {"type": "henyey_greenstein"}})"}),
              "/medium/phase/g");
    EXPECT_EQ(errorPointer({R"(/medium={"phase": {"type": "rayleigh"}})"}), "/medium/phase/type");
    EXPECT_EQ(errorPointer({R"(/medium={"phase": {"type": "isotropic", "g": 0.5}})"}),
              "/medium/phase/g");
    EXPECT_EQ(errorPointer({R"(/shapes/1/interior_medium={"sigma_a": [1, 2]})"}),
              "/shapes/1/interior_medium/sigma_a");
    EXPECT_EQ(errorPointer({R"(/shapes/1={"type": "sphere", "radius": 0.5})"}),
              "/shapes/1/material");
}

// The direct integrator ignores media, so it refuses them, naming where the first is declared.
TEST(MediaConfig, DirectIntegratorRefusesMedia) {
    const std::string direct = R"(/integrator={"type": "direct"})";
    EXPECT_EQ(errorPointer({direct, R"(/medium={"sigma_s": 1})"}), "/medium");
    EXPECT_EQ(errorPointer({direct, R"(/shapes/1/interior_medium={})"}),
              "/shapes/1/interior_medium");
    EXPECT_EQ(errorPointer({direct}), "<no error>");
}

}  // namespace
}  // namespace rr::test
