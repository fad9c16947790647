// PMC-HI's mixture kernel (Lai et al. 2007 eq. 7) and the density that weighs its samples
// (eq. 8's denominator), at a fixed shading point under a quad area light and a constant
// environment, with fixed α, cone axis d and cone angle β; one case with one component for all
// lights (the scene's light selection; a second environment, so that an escaped direction's
// density must sum both):
//  - the directions of a population's samples that find emission follow K = Σ α_k h_k: χ²
//    over the sphere, where each h_k is the estimator's own density with α one-hot on k
//    (so the test also checks that K sums every component that could have drawn a sample —
//    the environment's draws towards the quad are blocked, and the quad's density counts
//    instead), with the samples that found nothing in a cell of their own;
//  - negative controls: the quad's density 10 % high, or a cone 5 % wider, are rejected;
//  - each found sample's K is the density the χ² test integrates, at its direction (so the
//    quad's own draws, weighed by the pdf its sampler reports, agree with the pdf of the
//    point a ray in their direction finds);
//  - a cone of 10⁻³ radians (kMinConeAngle) keeps its own density in every draw's K (the
//    float test of 1 − cos it replaced dropped it from 11 % of them here).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sampling/warps.h"
#include "scene/lights/area_light.h"
#include "scene/shape.h"
#include "support/chi2.h"
#include "support/histograms.h"
#include "support/scene_testing.h"
#include "support/test_random.h"
#include "techniques/pmc/pmc_hi_estimator.h"

namespace rr::test {
namespace {

using pmc::PmcHiEstimator;
using Parameters = PmcHiEstimator::MixtureParameters;

// A shading point at the origin of a scene with no other geometry than its lights: the
// estimator's view of a surface vertex (integrators/scattering_vertex.h), with its decisions
// drawn from a counter-based stream.
class ScenePoint final : public ShadingPoint {
  public:
    ScenePoint(const Scene& scene, const Material& material, const Frame& frame, const Vec3& wo)
        : scene_(scene), material_(material), frame_(frame), wo_(frame.toLocal(wo)) {}

    // The integrator's light sampling (PMC-HI's one component for all lights): the scene's
    // selection, then the light's own sampler.
    bool sampleLight(uint32_t, uint32_t, const LightStandIns*, LightSample* ls, float* pdf,
                     const Light** light) override {
        float pmf;
        *light = scene_.lightSelector().select(uniform(kSeed, draws_++), Vec3(0.0f), &pmf);
        if (!*light || !(*light)->sample(lightReference(), uniform2(kSeed, draws_++), 0.0f, ls))
            return false;
        *pdf = pmf * ls->pdf;
        return true;
    }
    Rgb scattering(const Vec3& wi) const override {
        return material_.eval(context(), wo_, frame_.toLocal(wi));
    }
    float scatteringPdf(const Vec3&) const override { return 0; }
    float scatteringSamples() const override { return 0; }
    Rgb visibility(const LightSample& ls, bool infinite, float* survival) override {
        *survival = 1;
        Ray shadow{Vec3(0.0f), ls.direction};
        if (!infinite) shadow.tMax = length(ls.position) * (1 - 1e-4f);
        return Rgb(scene_.occluded(shadow) ? 0.0f : 1.0f);
    }
    Rgb contribution(const Rgb& f, const Rgb& le, const Rgb& tr, float misWeight,
                     float density) const override {
        return f * le * tr * (misWeight / density);
    }
    float decide1D(Decision, uint32_t, uint32_t) const override { return uniform(kSeed, draws_++); }
    Vec2 decide2D(Decision, uint32_t, uint32_t) const override { return uniform2(kSeed, draws_++); }
    const Frame* frame() const override { return &frame_; }
    Vec3 position() const override { return Vec3(0.0f); }
    bool scatteringShape(const LobePeakSources*, ScatteringShape*) const override { return false; }
    bool sampleScattering(float uLobe, const Vec2& u, Vec3* wi, float* pdf) const override {
        BsdfSample bs;
        if (!material_.sample(context(), wo_, uLobe, u, &bs) || bs.isSpecular()) return false;
        *wi = frame_.toWorld(bs.wi);
        *pdf = bs.pdf;
        return true;
    }
    float sampleScatteringPdf(const Vec3& wi) const override {
        return material_.pdf(context(), wo_, frame_.toLocal(wi));
    }
    using ShadingPoint::incidentEmission;
    Rgb incidentEmission(const Vec3& wi, EmissionSource* source) override {
        EmissionSource found;
        SurfaceHit hit;
        Rgb le(0.0f);
        if (!scene_.intersect(Ray{Vec3(0.0f), wi}, &hit)) {
            found.escaped = true;
            const float pdf = infiniteLightPdf(wi, &le);
            if (source && source->withSelection) found.selectedLightPdf = pdf;
        } else if (const AreaLight* light = hit.shape->areaLight()) {
            found.areaLight = light;
            found.areaLightPdf = light->pdf(Vec3(0.0f), hit);
            if (source && source->withSelection)
                found.selectedLightPdf =
                    scene_.lightSelector().pmf(*light, Vec3(0.0f)) * found.areaLightPdf;
            le = light->emitted(hit.geometricNormal, -wi);
        }
        if (source)
            *source = EmissionSource{source->withSelection, found.areaLight, found.areaLightPdf,
                                     found.selectedLightPdf, found.escaped};
        return le;
    }
    bool sampleLightOf(const Light& light, const Vec2& u, LightSample* ls) const override {
        return light.sample(lightReference(), u, 0.0f, ls);
    }
    float infiniteLightPdf(const Vec3& wi, Rgb* radiance) const override {
        float pdf = 0;
        *radiance = Rgb(0.0f);
        for (const Light* light : scene_.infiniteLights()) {
            pdf += scene_.lightSelector().pmf(*light, Vec3(0.0f)) *
                   light->directionPdf(lightReference(), wi);
            *radiance += light->escapedRadiance(wi);
        }
        return pdf;
    }
    void add(const Rgb&) override {}

  private:
    static constexpr uint64_t kSeed = 2007;
    static const ShadingContext& context() {
        static const ShadingContext ctx{};
        return ctx;
    }
    const Scene& scene_;
    const Material& material_;
    Frame frame_;
    Vec3 wo_;
    mutable uint64_t draws_ = 0;
};

// The quad (1.1 × 0.9, facing down, ~0.2 sr) above the point and a constant environment, or
// two (whose densities for an escaped direction one component for all lights must sum). The
// camera is at the point, the origin, so that rendering space is the file's.
LoadedScene quadAndEnvironment(bool twoEnvironments) {
    return loadSceneText(
        R"({"render": {"resolution": [4, 4]},
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1]},
        "shapes": [{"type": "quad", "corner": [-0.3, -0.7, 2], "edge_u": [0, 1.1, 0.2],
                    "edge_v": [0.9, 0, 0.1], "emission": {"radiance": 5}}],
        "lights": [{"type": "environment", "radiance": 0.5})" +
        std::string(twoEnvironments ? R"(, {"type": "environment", "radiance": 0.2})" : "") + "]}");
}

struct Case {
    const char* name;
    const char* material;
    std::vector<double> alpha;  // the BSDF, the quad, the environment(s), the cone
    Vec3 coneAxis;
    float coneAngle;
    // One component for all lights (the quad and two environments, α its quad's and
    // environments' entries summed), drawn by the scene's light selection (by power).
    bool oneForAll = false;
};

const Case kCases[] = {
    // The cone about a direction between the quad and the zenith, overlapping both.
    {"lambert",
     R"({"type":"lambert","albedo":0.8})",
     {0.3, 0.3, 0.2, 0.2},
     Vec3(0.3f, 0, 1),
     0.35f},
    // A glossy lobe, the cone narrow and inside the quad's directions.
    {"blinn",
     R"({"type":"blinn","reflectance":1,"ior":1.5,"roughness":0.2})",
     {0.4, 0.2, 0.2, 0.2},
     Vec3(0.12f, -0.05f, 1),
     0.2f},
    // Iteration 0's kernel: no cone.
    {"no_cone",
     R"({"type":"blinn","reflectance":1,"ior":1.5,"roughness":0.2})",
     {1 / 3.0, 1 / 3.0, 1 / 3.0, 0},
     Vec3(0, 0, 1),
     0.0f},
    {"one_for_all_lights",
     R"({"type":"blinn","reflectance":1,"ior":1.5,"roughness":0.2})",
     {0.3, 0.25, 0.25, 0.2},
     Vec3(0.3f, 0, 1),
     0.35f,
     true},
};

// χ² runs: the cases and two negative controls.
const Chi2Family kChi2(int(std::size(kCases)) + 2);

constexpr uint32_t kPopulation = PmcHiEstimator::kMaxPopulation;
constexpr uint32_t kPopulations = 4000;  // ~10⁶ draws

// The point, its material and the estimator for one case.
struct Fixture {
    LoadedScene scene;
    std::unique_ptr<Material> bsdf;
    PmcHiEstimator estimator;
    std::unique_ptr<ScenePoint> point;
    uint32_t quad = 0, environment = 0;  // their components (one light each)

    static pmc::PmcHiSettings settings(const Case& c) {
        pmc::PmcHiSettings s;
        s.lightComponents = c.oneForAll ? pmc::LightComponents::One : pmc::LightComponents::Each;
        return s;
    }
    explicit Fixture(const Case& c)
        : scene(quadAndEnvironment(c.oneForAll)),
          bsdf(materialFromJson(c.material)),
          estimator(settings(c)) {
        estimator.prepare(*scene.scene, "/integrator/estimator");
        for (const Light* light : scene.scene->lights())
            (light->isInfinite() ? environment : quad) = 1 + light->index();
        const Frame frame(normalize(Vec3(0.1f, -0.15f, 1)));
        point = std::make_unique<ScenePoint>(*scene.scene, *bsdf, frame,
                                             normalize(Vec3(-0.5f, 0.2f, 1)));
    }
    // The case's α reordered to the estimator's components.
    Parameters parameters(const Case& c) const {
        if (c.oneForAll)
            return {{c.alpha[0], c.alpha[1] + c.alpha[2], c.alpha[3]}, c.coneAxis, c.coneAngle};
        Parameters p{std::vector<double>(4, 0.0), c.coneAxis, c.coneAngle};
        p.alpha[0] = c.alpha[0];
        p.alpha[quad] = c.alpha[1];
        p.alpha[environment] = c.alpha[2];
        p.alpha[3] = c.alpha[3];
        return p;
    }
};

DirectionHistogram cells() {
    // Over the sphere; the shading horizon (tilted) and the lights' outlines cross cells,
    // which the histogram's edge rule refines.
    return DirectionHistogram(25, 50);
}

// Expected counts of component k's found samples for `draws` draws: ∫ h_k over each cell,
// over the directions that reach the quad and those that escape separately, so that the quad's
// outline, where one component for all lights jumps from the environments' density to the
// quad's, is a boundary of each integrand's support (which the histogram refines).
std::vector<double> componentCounts(Fixture& s, Parameters p, uint32_t k, double draws) {
    const double share = p.alpha[k];
    std::fill(p.alpha.begin(), p.alpha.end(), 0.0);
    p.alpha[k] = 1;
    std::vector<double> total;
    for (bool towardsQuad : {true, false}) {
        const std::vector<double> part = cells().expected(
            [&](const Vec3& w) {
                SurfaceHit hit;
                if (s.scene.scene->intersect(Ray{Vec3(0.0f), w}, &hit) != towardsQuad) return 0.0;
                return double(s.estimator.mixtureDensity(*s.point, p, w));
            },
            draws * share);
        total.resize(part.size(), 0.0);
        for (size_t i = 0; i < part.size(); ++i)
            total[i] += part[i];
    }
    return total;
}

struct Observed {
    std::vector<double> counts;  // found samples per cell; the last cell: those that found nothing
    size_t found = 0;
    size_t densityMismatches = 0;  // K off the density at the sample's direction by > 10⁻⁴
};

Observed drawDirections(Fixture& s, const Parameters& p) {
    DirectionHistogram h = cells();
    Observed o;
    for (uint32_t i = 0; i < kPopulations; ++i)
        for (const PmcHiEstimator::MixtureSample& m :
             s.estimator.drawPopulation(*s.point, p, kPopulation)) {
            h.add(m.direction);
            ++o.found;
            const float k = s.estimator.mixtureDensity(*s.point, p, m.direction);
            if (!(std::abs(m.density - k) <= 1e-4f * k)) ++o.densityMismatches;
        }
    o.counts = h.counts();
    o.counts.back() = double(kPopulations) * kPopulation - double(o.found);
    return o;
}

// Σ_k weight_k · counts_k, and the draws that found nothing in the last cell.
std::vector<double> expectedCounts(const std::vector<std::vector<double>>& components,
                                   const std::vector<double>& weights) {
    std::vector<double> total(components[0].size(), 0.0);
    double sum = 0;
    for (size_t k = 0; k < components.size(); ++k)
        for (size_t i = 0; i + 1 < total.size(); ++i) {
            total[i] += weights[k] * components[k][i];
            sum += weights[k] * components[k][i];
        }
    total.back() = double(kPopulations) * kPopulation - sum;
    return total;
}

class PmcHiMixture : public ::testing::TestWithParam<Case> {};

TEST_P(PmcHiMixture, FoundSamplesFollowTheDensityThatWeighsThem) {
    const Case& c = GetParam();
    Fixture s(c);
    const Parameters p = s.parameters(c);
    const Observed observed = drawDirections(s, p);
    const double draws = double(kPopulations) * kPopulation;
    std::vector<std::vector<double>> components;
    for (uint32_t k = 0; k < p.alpha.size(); ++k)
        components.push_back(p.alpha[k] > 0 ? componentCounts(s, p, k, draws)
                                            : std::vector<double>(cells().counts().size(), 0.0));
    const std::vector<double> expected =
        expectedCounts(components, std::vector<double>(components.size(), 1.0));
    std::printf("found %.4f of the draws (expected %.4f)\n", observed.found / draws,
                1 - expected.back() / draws);
    EXPECT_EQ(observed.densityMismatches, 0u) << "of " << observed.found;
    kChi2.expectFits(chi2GoodnessOfFit(observed.counts, expected), c.name);

    if (std::string(c.name) != "blinn") return;
    // Negative controls on the case whose cone overlaps the quad.
    kChi2.expectRejects(
        chi2GoodnessOfFit(observed.counts, expectedCounts(components, {1, 1.1, 1, 1})),
        "the quad's density 10 % high");
    Parameters wider = p;
    wider.coneAngle *= 1.05f;
    components[3] = componentCounts(s, wider, 3, draws);
    kChi2.expectRejects(
        chi2GoodnessOfFit(observed.counts, expectedCounts(components, {1, 1, 1, 1})),
        "a cone 5 % wider");
}

INSTANTIATE_TEST_SUITE_P(Kernels, PmcHiMixture, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& param) {
                             return std::string(param.param.name);
                         });

TEST(PmcHiMixtureNarrowCone, EveryConeDrawKeepsItsOwnDensity) {
    Case c = kCases[1];
    c.coneAngle = PmcHiEstimator::kMinConeAngle;
    Fixture s(c);
    const Parameters p = s.parameters(c);
    const double coneTerm =
        p.alpha[3] * uniformConePdf(2 * std::pow(std::sin(0.5 * c.coneAngle), 2));
    const uint32_t populations = 1000;
    uint32_t coneDraws = 0, withoutOwn = 0;
    for (uint32_t i = 0; i < populations; ++i)
        for (const PmcHiEstimator::MixtureSample& m :
             s.estimator.drawPopulation(*s.point, p, kPopulation)) {
            if (m.component != 3) continue;
            ++coneDraws;
            if (m.density < coneTerm * (1 - 1e-4)) ++withoutOwn;
        }
    // Deterministic mixture sampling gives the cone ⌊N α⌋ or one more draw per population, and
    // every cone direction (inside the quad) finds emission.
    EXPECT_GE(coneDraws, populations * uint32_t(kPopulation * p.alpha[3]));
    EXPECT_EQ(withoutOwn, 0u) << "of " << coneDraws << " cone draws";
}

}  // namespace
}  // namespace rr::test
