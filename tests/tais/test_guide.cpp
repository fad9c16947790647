// TAIS's decisions (techniques/tais/map_guide.h) sample exactly the densities they claim:
//  - scatter direction, eq. (2): directions from α · map + (1 − α) · BSDF sampling fit the
//    mixture density bsdfPdf() reports (χ²), and every sample's weight is f / that density;
//  - bifurcation, eq. (2) over {reflect, transmit}: reflection is chosen with probability
//    α q + (1 − α) F, and the sample's pdf says so;
//  - light selection, eq. (2) over the lights: the chosen light's frequency matches the
//    mixture pmf, at the first vertex and, from the vertex's own entries, at a deeper one;
// each with a negative control that must fail. The maps here are 60 % credited and 40 % uniform
// for the decision tested, so they mix in their credited part with α = 0.6 · 0.5
// (TaisSettings::alphaFollowsEvidence); a last test checks that a decision without credit is
// standard sampling's, and that the paper's constant α mixes in the whole map.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/materials/dielectric.h"
#include "scene/materials/lambert.h"
#include "support/chi2.h"
#include "support/histograms.h"
#include "support/scene_testing.h"
#include "techniques/tais/map_guide.h"

namespace rr::test {
namespace {

using tais::PixelMaps;
using tais::TaisSettings;

constexpr int kSamples = 200000;
const Chi2Family kChi2(10);
// The share of each test map's mass, for the decision tested, that samples credited, and the
// α it gives.
constexpr double kEvidence = 0.6;
constexpr float kAlpha = 0.5f * float(kEvidence);

// Adds a uniform part to `map` so that its credited part is kEvidence of the mass of cells
// [first, first + count).
void makeCreditedShare(tais::InvertedMap1D& map, int first, int count) {
    const double credited = map.sliceTotal(first, count, tais::MapPart::Credited);
    map.accumulateUniform(credited * (1 - kEvidence) / kEvidence / count);
}

// A scene with three lights (for light selection); only its light list and selector are used.
const LoadedScene& threeLights() {
    static const LoadedScene scene = loadSceneText(R"({
      "camera": { "type": "pinhole", "position": [0, 0, 5], "look_at": [0, 0, 0], "fov": 40 },
      "render": { "resolution": [8, 8] },
      "shapes": [ { "type": "quad", "corner": [-1, -1, 0], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0], "material": { "type": "lambert", "albedo": 0.5 } } ],
      "lights": [ { "type": "point", "position": [0, 0, 2], "intensity": 1 },
                  { "type": "point", "position": [1, 0, 2], "intensity": 1 },
                  { "type": "point", "position": [0, 1, 2], "intensity": 1 } ]
    })");
    return scene;
}

TaisSettings settingsWith(tais::MapKind kind) {
    TaisSettings s;
    s.automatic = false;
    s.enabled[static_cast<int>(kind)] = true;
    s.scatterDirectionSize = 16;
    return s;
}

// A scatter-direction map with most of its mass in a band of cells around one direction.
PixelMaps directionMaps(const TaisSettings& s) {
    PixelMaps maps = PixelMaps::uniform(s, 3);
    const int n = s.scatterDirectionSize;
    std::vector<double> w(size_t(n) * n, 0.05);
    const Vec2 peak = tais::directionToMap(normalize(Vec3(0.5f, 0.2f, 0.8f)));
    const int px = int(peak.x * n), py = int(peak.y * n);
    for (int y = std::max(py - 1, 0); y <= std::min(py + 1, n - 1); ++y)
        for (int x = std::max(px - 2, 0); x <= std::min(px + 2, n - 1); ++x)
            w[size_t(y) * n + x] = 20;
    tais::InvertedMap2D& map = maps.scatterDirection[0];
    map = tais::InvertedMap2D::fromWeights(w, n, n);
    map.accumulateUniform(map.total() * (1 - kEvidence) / kEvidence / (n * n));
    return maps;
}

struct DirectionRun {
    DirectionHistogram observed{12, 48, 0.0};  // the upper hemisphere; below: extra cell
    bool weightsMatch = true;
    std::string weightFailure;
};

// Samples the first non-specular bounce through the guide at a tilted shading frame.
DirectionRun sampleDirections(const PixelMaps& maps, const TaisSettings& s, const Frame& frame,
                              const Vec3& woLocal) {
    const Scene& scene = *threeLights().scene;
    const Lambert lambert(Rgb(0.8f));
    const Sampler sampler(SamplerType::Independent, 7, 1);
    const std::vector<const InvertibleLight*> invertible(3, nullptr);
    const ShadingContext ctx{Vec2(0.5f, 0.5f), Vec3(0.0f)};
    DirectionRun run;
    for (int i = 0; i < kSamples; ++i) {
        const PixelSample sample = sampler.at(uint32_t(i), 0);
        tais::MapGuide guide(scene, sample, maps, s, invertible);
        BsdfSample bs;
        if (!guide.sampleBsdf(0, lambert, ctx, frame, woLocal, Rgb(0.0f), &bs)) {
            run.observed.add(Vec3(0, 0, -1));  // below the surface: the extra cell
            continue;
        }
        run.observed.add(bs.wi);
        // The weight is f·cos / the mixture density at this bounce (a fresh guide: bounce 0).
        tais::MapGuide fresh(scene, sample, maps, s, invertible);
        const float pdf = fresh.bsdfPdf(0, lambert, ctx, frame, woLocal, bs.wi);
        const Rgb expected = lambert.eval(ctx, woLocal, bs.wi) * (1.0f / pdf);
        if (run.weightsMatch && (std::abs(bs.pdf - pdf) > 1e-4f * pdf ||
                                 std::abs(bs.weight.g - expected.g) > 1e-4f * expected.g)) {
            run.weightsMatch = false;
            run.weightFailure = "pdf " + std::to_string(bs.pdf) + " vs " + std::to_string(pdf) +
                                ", weight " + std::to_string(bs.weight.g) + " vs " +
                                std::to_string(expected.g);
        }
    }
    return run;
}

// The mixture density, in the local frame, as bsdfPdf() reports it.
std::function<double(const Vec3&)> mixtureDensity(const PixelMaps& maps, const TaisSettings& s,
                                                  const Frame& frame, const Vec3& woLocal) {
    return [&maps, &s, frame, woLocal](const Vec3& wi) {
        static const std::vector<const InvertibleLight*> invertible(3, nullptr);
        const Sampler sampler(SamplerType::Independent, 0, 1);
        const PixelSample sample = sampler.at(0, 0);
        const tais::MapGuide guide(*threeLights().scene, sample, maps, s, invertible);
        const Lambert lambert(Rgb(0.8f));
        const ShadingContext ctx{Vec2(0.5f, 0.5f), Vec3(0.0f)};
        return double(guide.bsdfPdf(0, lambert, ctx, frame, woLocal, wi));
    };
}

TEST(TaisGuide, ScatterDirectionSamplesTheMixtureOfMapAndBsdf) {
    const TaisSettings s = settingsWith(tais::MapKind::ScatterDirection);
    const PixelMaps maps = directionMaps(s);
    const Frame frame(normalize(Vec3(0.3f, -0.2f, 1.0f)));
    const Vec3 wo = normalize(Vec3(0.2f, 0.1f, 1.0f));
    const DirectionRun run = sampleDirections(maps, s, frame, wo);
    EXPECT_TRUE(run.weightsMatch) << run.weightFailure;
    // The reported density is the mixture of the map's credited part, α scaled by its share.
    const Vec3 wi = normalize(Vec3(0.3f, 0.1f, 0.9f));
    const Lambert lambert(Rgb(0.8f));
    const ShadingContext ctx{Vec2(0.5f, 0.5f), Vec3(0.0f)};
    const float mapPdf = tais::directionPdfFromMap(maps.scatterDirection[0].pdf(
        tais::directionToMap(frame.toWorld(wi)), tais::MapPart::Credited));
    EXPECT_NEAR(mixtureDensity(maps, s, frame, wo)(wi),
                kAlpha * mapPdf + (1 - kAlpha) * lambert.pdf(ctx, wo, wi), 1e-5);
    // Map samples below the surface end the path (f = 0): the extra cell expects their share.
    const auto pdf = mixtureDensity(maps, s, frame, wo);
    std::vector<double> expected = run.observed.expected(pdf, kSamples);
    double inside = 0;
    for (size_t i = 0; i + 1 < expected.size(); ++i)
        inside += expected[i];
    expected.back() = kSamples - inside;
    kChi2.expectFits(chi2GoodnessOfFit(run.observed.counts(), expected), "scatter direction");

    // Negative control: the BSDF's density alone (α = 0) does not describe these samples.
    TaisSettings standard = s;
    standard.enabled[static_cast<int>(tais::MapKind::ScatterDirection)] = false;
    const PixelMaps none = PixelMaps::uniform(standard, 3);
    // Its in-hemisphere shape, scaled to the same total there, so that only the shape differs.
    std::vector<double> wrong =
        run.observed.expected(mixtureDensity(none, standard, frame, wo), inside);
    wrong.back() = expected.back();
    kChi2.expectRejects(chi2GoodnessOfFit(run.observed.counts(), wrong), "BSDF density alone");
}

TEST(TaisGuide, BifurcationChoosesReflectionWithTheMixedProbability) {
    TaisSettings s = settingsWith(tais::MapKind::Bifurcation);
    PixelMaps maps = PixelMaps::uniform(s, 3);
    // Vertex 0: the map prefers reflection 9 : 1.
    std::vector<double> w(size_t(2 * s.bifurcationVertices), 1.0);
    w[size_t(tais::bifurcationCell(0, true))] = 9;
    maps.bifurcation = tais::InvertedMap1D::fromWeights(w);
    makeCreditedShare(*maps.bifurcation, tais::bifurcationCell(0, true), 2);
    const Dielectric glass(1.5f, Rgb(1.0f), Rgb(1.0f));
    const Vec3 wo = normalize(Vec3(0.1f, 0.0f, 1.0f));
    const ShadingContext ctx{Vec2(0.5f, 0.5f), Vec3(0.0f)};
    const float fresnel = glass.reflectProbability(wo);
    const double expectedReflect = kAlpha * 0.9 + (1 - kAlpha) * fresnel;
    const Sampler sampler(SamplerType::Independent, 3, 1);
    const std::vector<const InvertibleLight*> invertible(3, nullptr);
    double reflections = 0;
    bool pdfsMatch = true;
    for (int i = 0; i < kSamples; ++i) {
        const PixelSample sample = sampler.at(uint32_t(i), 0);
        tais::MapGuide guide(*threeLights().scene, sample, maps, s, invertible);
        BsdfSample bs;
        ASSERT_TRUE(guide.sampleBsdf(0, glass, ctx, Frame(), wo, Rgb(0.0f), &bs));
        const bool reflected = (bs.lobe & kReflection) != 0;
        reflections += reflected;
        const double claimed = reflected ? expectedReflect : 1 - expectedReflect;
        pdfsMatch = pdfsMatch && std::abs(bs.pdf - claimed) < 1e-5;
        // The weight undoes the choice: F·R / P for reflection, (1 − F)·T/η² / (1 − P) else.
        const double value = reflected ? fresnel : (1 - fresnel) / (1.5 * 1.5);
        pdfsMatch = pdfsMatch && std::abs(bs.weight.r - value / claimed) < 1e-4 * value / claimed;
    }
    EXPECT_TRUE(pdfsMatch);
    const std::vector<double> observed{reflections, kSamples - reflections};
    kChi2.expectFits(
        chi2GoodnessOfFit(observed, {kSamples * expectedReflect, kSamples * (1 - expectedReflect)}),
        "bifurcation");
    kChi2.expectRejects(chi2GoodnessOfFit(observed, {kSamples * fresnel, kSamples * (1 - fresnel)}),
                        "Fresnel alone");
}

// Draws kSamples light samples at `vertex` through the guide and counts the lights chosen. With
// point lights a sample's density is its selection probability alone: it must be
// claimed[light].
std::vector<double> selectLights(const PixelMaps& maps, const TaisSettings& s, uint32_t vertex,
                                 const std::vector<double>& claimed, uint64_t seed) {
    const Sampler sampler(SamplerType::Independent, seed, 1);
    const std::vector<const InvertibleLight*> invertible(3, nullptr);
    std::vector<double> observed(3, 0.0);
    int wrongPdfs = 0;
    for (int i = 0; i < kSamples; ++i) {
        const PixelSample sample = sampler.at(uint32_t(i), 0);
        tais::MapGuide guide(*threeLights().scene, sample, maps, s, invertible);
        LightSample ls;
        float pdf;
        const Light* light;
        if (!guide.sampleLight(vertex, 0, 1, nullptr, Vec3(0.1f, 0.2f, 0.0f), 0, &ls, &pdf,
                               &light)) {
            ADD_FAILURE() << "no light sampled";
            break;
        }
        observed[size_t(light->index())] += 1;
        wrongPdfs += !(std::abs(pdf - claimed[size_t(light->index())]) <= 1e-6);  // NaN: wrong
    }
    EXPECT_EQ(wrongPdfs, 0) << "at vertex " << vertex;
    return observed;
}

std::vector<double> times(double n, std::vector<double> v) {
    for (double& x : v)
        x *= n;
    return v;
}

// Eq. (2) over the lights, with q the map's probabilities and the selector's 1/3 (equal lights).
std::vector<double> mixture(const std::vector<double>& q) {
    std::vector<double> p;
    for (double qi : q)
        p.push_back(kAlpha * qi + (1 - kAlpha) / 3.0);
    return p;
}

TEST(TaisGuide, LightSelectionMixesTheMapWithTheSelector) {
    const TaisSettings s = settingsWith(tais::MapKind::LightSelection);
    PixelMaps maps = PixelMaps::uniform(s, 3);
    maps.lightSelection = tais::InvertedMap1D::fromWeights(std::vector<double>{1, 0.0001, 3});
    makeCreditedShare(*maps.lightSelection, 0, 3);
    const std::vector<double> claimed = mixture({1 / 4.0001, 0.0001 / 4.0001, 3 / 4.0001});
    const std::vector<double> observed = selectLights(maps, s, 0, claimed, 5);
    kChi2.expectFits(chi2GoodnessOfFit(observed, times(kSamples, claimed)), "light selection");
    kChi2.expectRejects(chi2GoodnessOfFit(observed, times(kSamples, {1 / 3.0, 1 / 3.0, 1 / 3.0})),
                        "uniform selection alone");
}

// Beyond the paper: with light_selection_vertices = 3, vertex 2 chooses from its own entries
// (here preferring light 1), mixed with the selector by its own credited share; with the
// paper's constant α, from its whole entries (credited and uniform); vertex 3 is past the map
// and uses the selector alone.
TEST(TaisGuide, DeeperVerticesSelectLightsFromTheirOwnEntries) {
    TaisSettings s = settingsWith(tais::MapKind::LightSelection);
    s.lightSelectionVertices = 3;
    PixelMaps maps = PixelMaps::uniform(s, 3);
    const std::vector<double> w{1,   0.0001, 3,   // vertex 0
                                1,   1,      1,   // vertex 1
                                0.5, 6,      1};  // vertex 2
    maps.lightSelection = tais::InvertedMap1D::fromWeights(w);
    makeCreditedShare(*maps.lightSelection, 6, 3);
    const std::vector<double> claimed = mixture({0.5 / 7.5, 6 / 7.5, 1 / 7.5});
    const std::vector<double> observed = selectLights(maps, s, 2, claimed, 13);
    kChi2.expectFits(chi2GoodnessOfFit(observed, times(kSamples, claimed)),
                     "light selection at vertex 2");
    kChi2.expectRejects(
        chi2GoodnessOfFit(observed,
                          times(kSamples, mixture({1 / 4.0001, 0.0001 / 4.0001, 3 / 4.0001}))),
        "vertex 0's entries");
    TaisSettings paper = s;
    paper.alphaFollowsEvidence = false;
    std::vector<double> whole;
    for (int light = 0; light < 3; ++light)
        whole.push_back(paper.alpha * maps.lightSelection->weight(6 + light) /
                            maps.lightSelection->sliceTotal(6, 3) +
                        (1 - paper.alpha) / 3.0);
    kChi2.expectFits(
        chi2GoodnessOfFit(selectLights(maps, paper, 2, whole, 19), times(kSamples, whole)),
        "vertex 2, the paper's constant α and whole entries");
    const std::vector<double> selector{1 / 3.0, 1 / 3.0, 1 / 3.0};
    kChi2.expectFits(
        chi2GoodnessOfFit(selectLights(maps, s, 3, selector, 17), times(kSamples, selector)),
        "vertex 3, past the map: the selector alone");
}

// Beyond the paper: where a world map has no credit for a decision, the decision is standard
// sampling's: at a bifurcation vertex no credited sample reached, where the paper's constant α
// and the map's even entries give 0.25 + 0.5 F, and in a scatter-direction map that only black
// pixels fed, whose uniform half would send a quarter of the bounces below the surface. With
// alpha_follows_evidence false the whole map is mixed in with α.
TEST(TaisGuide, ADecisionWithoutCreditIsStandardSampling) {
    const Scene& scene = *threeLights().scene;
    const Sampler sampler(SamplerType::Independent, 11, 1);
    const std::vector<const InvertibleLight*> invertible(3, nullptr);
    const ShadingContext ctx{Vec2(0.5f, 0.5f), Vec3(0.0f)};
    for (const bool follows : {true, false}) {
        TaisSettings s;
        s.automatic = false;
        for (auto kind : {tais::MapKind::Bifurcation, tais::MapKind::ScatterDirection})
            s.enabled[static_cast<int>(kind)] = true;
        s.scatterDirectionSize = 16;
        s.alphaFollowsEvidence = follows;
        PixelMaps maps = PixelMaps::uniform(s, 3);
        std::vector<double> w(size_t(2 * s.bifurcationVertices), 0.0);
        w[size_t(tais::bifurcationCell(1, true))] = 2;  // only vertex 1 has credit
        maps.bifurcation = tais::InvertedMap1D::fromWeights(w);
        maps.bifurcation->accumulateUniform(1);
        const float a = follows ? 0.0f : s.alpha;

        const Dielectric glass(1.5f, Rgb(1.0f), Rgb(1.0f));
        const Vec3 wo = normalize(Vec3(0.1f, 0.0f, 1.0f));
        const float reflect = a * 0.5f + (1 - a) * glass.reflectProbability(wo);
        const Lambert lambert(Rgb(0.8f));
        const Frame frame(normalize(Vec3(0.3f, -0.2f, 1.0f)));
        const int n = 20000;
        int below = 0, wrongPdfs = 0;
        for (int i = 0; i < n; ++i) {
            const PixelSample sample = sampler.at(uint32_t(i), 0);
            tais::MapGuide guide(scene, sample, maps, s, invertible);
            BsdfSample bs;
            ASSERT_TRUE(guide.sampleBsdf(0, glass, ctx, Frame(), wo, Rgb(0.0f), &bs));
            wrongPdfs +=
                !(std::abs(bs.pdf - ((bs.lobe & kReflection) ? reflect : 1 - reflect)) <= 1e-6f);
            tais::MapGuide direction(scene, sample, maps, s, invertible);
            if (!direction.sampleBsdf(0, lambert, ctx, frame, wo, Rgb(0.0f), &bs)) {
                ++below;
                continue;
            }
            // Without credit the direction's density is the material's own, its weight finite.
            if (follows)
                wrongPdfs += !(std::abs(bs.pdf - lambert.pdf(ctx, wo, bs.wi)) <= 1e-5f * bs.pdf) ||
                             !bs.weight.isFinite();
        }
        EXPECT_EQ(wrongPdfs, 0) << "alpha_follows_evidence " << follows;
        if (follows) {
            EXPECT_EQ(below, 0);
        } else {  // the uniform map's half below the surface, drawn with probability α: z-test
            const double p = 0.5 * s.alpha;
            EXPECT_LT(std::abs(below - n * p), 5 * std::sqrt(n * p * (1 - p)));
        }
    }
}

}  // namespace
}  // namespace rr::test
