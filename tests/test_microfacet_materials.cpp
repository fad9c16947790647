// Tests of the glossy half-vector materials: Blinn (Torrance–Sparrow with the Blinn–Phong
// distribution), Cook–Torrance (Beckmann, Smith masking) and Ashikhmin–Shirley (anisotropic
// Phong). For each, at extreme parameters and at normal, oblique, grazing and lower-side
// incidence: χ² of sample() against pdf() (zoomed onto narrow lobes), weight = eval/pdf and
// finite, directional albedo ≤ 1.01 (pbrt's check), reciprocity, eval against the papers'
// formulas, the mirror peak a local maximum, Ashikhmin–Shirley's cone peaks on the lobe's
// ridge, a negative control per family, and the JSON keys.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iterator>
#include <memory>
#include <string>
#include <tuple>

#include "config/config_error.h"
#include "scene/materials/ashikhmin_shirley.h"
#include "scene/materials/blinn.h"
#include "scene/materials/cook_torrance.h"
#include "scene/materials/dielectric.h"
#include "scene/materials/lambert.h"
#include "support/bsdf_checks.h"
#include "support/chi2.h"
#include "support/scene_testing.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

// Every χ² run in this file: 4 incident directions × (Blinn at 2 roughnesses, Cook–Torrance
// at 2, Ashikhmin–Shirley at 3 roughness pairs), 3 negative controls, and the accounting of
// declined samples (1 fit, 1 negative control).
constexpr int kDirections = 4;
constexpr int kRuns = kDirections * (2 + 2 + 3) + 3 + 2;
const Chi2Family kChi2(kRuns);
constexpr int kSamples = 1000000;
const ShadingContext kCtx{};

// Normal, oblique, on the lower side (two-sided materials), grazing.
const Vec3 kWos[kDirections] = {directionFromDegrees(0, 0), directionFromDegrees(40, 30),
                                directionFromDegrees(120, -60), directionFromDegrees(87, 200)};

std::unique_ptr<Material> blinn(float roughness, const Rgb& reflectance = Rgb(0.9f, 0.8f, 0.7f)) {
    return std::make_unique<Blinn>(constantTexture(reflectance), constantTexture(roughness), 1.5f);
}
std::unique_ptr<Material> cookTorrance(float alpha) {
    return std::make_unique<CookTorrance>(constantTexture(Rgb(0.9f, 0.8f, 0.7f)),
                                          constantTexture(alpha), 1.5f);
}
// Roughnesses (n = 1/roughness), as the two-stage paper quotes them.
std::unique_ptr<AshikhminShirley> ashikhminShirley(float roughnessU, float roughnessV,
                                                   const Rgb& rd = Rgb(0.5f),
                                                   const Rgb& rs = Rgb(0.5f)) {
    return std::make_unique<AshikhminShirley>(constantTexture(rd), constantTexture(rs),
                                              constantTexture(roughnessU),
                                              constantTexture(roughnessV), false);
}

// One material at one parameter setting; `capDegrees` > 0 zooms the histogram onto a cap of
// that half-angle around the mirror direction (narrow lobes), 0 keeps the whole sphere.
struct MaterialCase {
    const char* name;
    std::function<std::unique_ptr<Material>()> make;
    double capDegrees;
};

const MaterialCase kCases[] = {
    {"blinn_roughness_0.02", [] { return blinn(0.02f); }, 60},
    {"blinn_roughness_1", [] { return blinn(1.0f); }, 0},
    {"cook_torrance_alpha_0.01", [] { return cookTorrance(0.01f); }, 3},
    {"cook_torrance_alpha_1", [] { return cookTorrance(1.0f); }, 0},
    {"ashikhmin_shirley_0.001_1", [] { return ashikhminShirley(0.001f, 1.0f); }, 0},
    {"ashikhmin_shirley_1_0.001", [] { return ashikhminShirley(1.0f, 0.001f); }, 0},
    {"ashikhmin_shirley_0.001_0.001", [] { return ashikhminShirley(0.001f, 0.001f); }, 10},
};

Vec3 mirrorOf(const Vec3& w) {
    return Vec3(-w.x, -w.y, w.z);
}

// `w` turned by `degrees` towards the unit vector `toward` (perpendicular to w).
Vec3 turned(const Vec3& w, const Vec3& toward, double degrees) {
    const float a = float(degrees * M_PI / 180);
    return normalize(w * std::cos(a) + toward * std::sin(a));
}

// The zoomed cap is centred a quarter of its radius off the mirror direction, across the plane
// of incidence. Towards grazing incidence the reflected lobe of a narrow distribution becomes
// a thin arc in that plane (squeezed across it by the factor 2 wo·h of the reflection map);
// through the cap's pole such an arc has a density ∝ 1/√(1 − z) in the cells' z coordinate,
// which the midpoint rule that integrates the expected counts underestimates (by ~1 % of
// all samples at θ = 87°, α = 0.01). Off the pole the arc crosses the rings at a finite
// distance and is integrated accurately.
BsdfHistogramLayout layoutFor(const MaterialCase& c, const Vec3& wo) {
    BsdfHistogramLayout layout;
    if (c.capDegrees == 0) return layout;
    const Vec3 mirror = mirrorOf(wo);
    const Vec3 across =
        wo.x == 0 && wo.y == 0 ? Vec3(1, 0, 0) : normalize(Vec3(-mirror.y, mirror.x, 0));
    layout.axis = turned(mirror, across, c.capDegrees / 4);
    layout.capDegrees = c.capDegrees;
    layout.zCells = 40;
    layout.phiCells = 24;
    return layout;
}

// --- χ², weights and energy, per material and incident direction ------------------------------

class SamplingChecks : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(SamplingChecks, SamplesFollowPdfWithFiniteWeightsAndAlbedoAtMostOne) {
    const auto [caseIndex, woIndex] = GetParam();
    const MaterialCase& c = kCases[caseIndex];
    const Vec3 wo = kWos[woIndex];
    const std::unique_ptr<Material> m = c.make();
    const uint64_t seed = 1000 + 10 * caseIndex + woIndex;
    const BsdfSamplingRun run = sampleBsdf(*m, kCtx, wo, seed, kSamples, layoutFor(c, wo));
    const std::string what = std::string(c.name) + ", wo = " + describe(wo);
    EXPECT_EQ(run.nonFinite, 0) << what;
    EXPECT_EQ(run.specular, 0) << what;
    EXPECT_EQ(run.weightMismatches, 0) << what << ": " << run.firstMismatch;
    std::printf("[info] %s: %.4f of the samples declined\n", what.c_str(),
                double(run.declined) / kSamples);
    kChi2.expectFits(run.outcome, what);

    const Rgb albedo = directionalAlbedo(*m, kCtx, wo, seed + 500);
    std::printf("[albedo] %s: %.4f %.4f %.4f\n", what.c_str(), albedo.r, albedo.g, albedo.b);
    EXPECT_LE(albedo.maxComponent(), 1.01f) << what;
}

INSTANTIATE_TEST_SUITE_P(MaterialsAndDirections, SamplingChecks,
                         ::testing::Combine(::testing::Range(0, int(std::size(kCases))),
                                            ::testing::Range(0, kDirections)),
                         [](const ::testing::TestParamInfo<std::tuple<int, int>>& param) {
                             std::string name = kCases[std::get<0>(param.param)].name;
                             for (char& ch : name)
                                 if (ch == '.') ch = '_';
                             return name + "_wo" + std::to_string(std::get<1>(param.param));
                         });

// Weights stay finite and equal eval/pdf up to the horizon (θ = 89°, 89.9°) and at the
// normal, for every case, and the albedo of the extreme Ashikhmin–Shirley settings (no
// diffuse with Rs = 0, diffuse only) stays below one as well.
// At the loader's smallest roughness (1e-6: exponent 10^6; Beckmann α 1e-4) sampling still
// works: the near-mirror lobe declines no more samples than at roughness 10^-3 (where the χ²
// runs above pass), and its weights and pdfs are finite.
int declinedSamples(const Material& m, const Vec3& wo, int samples) {
    int declined = 0;
    for (int i = 0; i < samples; ++i) {
        BsdfSample s;
        if (!m.sample(kCtx, wo, uniform(78, i, 2), uniform2(78, i), &s)) {
            ++declined;
            continue;
        }
        EXPECT_TRUE(std::isfinite(s.weight.g) && std::isfinite(s.pdf)) << describe(wo);
    }
    return declined;
}

TEST(Weights, SmallestAllowedRoughnessStillSamples) {
    const std::pair<std::unique_ptr<Material>, std::unique_ptr<Material>> pairs[] = {
        {blinn(1e-6f), blinn(1e-3f)},
        {cookTorrance(1e-4f), cookTorrance(1e-3f)},
        {ashikhminShirley(1e-6f, 1e-6f), ashikhminShirley(1e-3f, 1e-3f)}};
    constexpr int kDraws = 20000;
    for (const auto& [smallest, reference] : pairs)
        for (const Vec3& wo : {Vec3(0, 0, 1), directionFromDegrees(60, 20)})
            EXPECT_LE(declinedSamples(*smallest, wo, kDraws),
                      declinedSamples(*reference, wo, kDraws) + kDraws / 100)
                << describe(wo);
}

TEST(Weights, FiniteAndEvalOverPdfUpToTheHorizon) {
    const double thetas[] = {0, 20, 60, 85, 89, 89.9};
    for (const MaterialCase& c : kCases) {
        const std::unique_ptr<Material> m = c.make();
        for (double theta : thetas) {
            const Vec3 wo = directionFromDegrees(theta, 70);
            int mismatches = 0, nonFinite = 0;
            for (int i = 0; i < 20000; ++i) {
                BsdfSample s;
                if (!m->sample(kCtx, wo, uniform(7, i, 2), uniform2(7, i), &s)) continue;
                nonFinite += !s.weight.isFinite() || !std::isfinite(s.pdf) || !(s.pdf > 0);
                const Rgb f = m->eval(kCtx, wo, s.wi);
                const float pdf = m->pdf(kCtx, wo, s.wi);
                for (int ch = 0; ch < 3; ++ch)
                    mismatches += std::abs(s.weight[ch] * pdf - f[ch]) > 1e-3f * f[ch] + 1e-30f;
                mismatches += std::abs(s.pdf - pdf) > 1e-4f * pdf;
            }
            EXPECT_EQ(nonFinite, 0) << c.name << " at " << theta << "°";
            EXPECT_EQ(mismatches, 0) << c.name << " at " << theta << "°";
        }
    }
    for (const Rgb& rd : {Rgb(0.0f), Rgb(1.0f)})
        for (double theta : thetas) {
            const auto m = ashikhminShirley(0.5f, 0.5f, rd, Rgb(1.0f) - rd);
            const Rgb albedo = directionalAlbedo(*m, kCtx, directionFromDegrees(theta, 10), 8);
            EXPECT_LE(albedo.maxComponent(), 1.01f) << "Rd " << rd.r << " at " << theta << "°";
        }
}

TEST(Reciprocity, EvalOverCosineIsSymmetric) {
    for (const MaterialCase& c : kCases) {
        const double error = reciprocityError(*c.make(), kCtx, 9);
        std::printf("[reciprocity] %s: largest relative error %.2e\n", c.name, error);
        EXPECT_LT(error, 1e-5) << c.name;
    }
}

// --- eval against the papers' formulas, evaluated independently in double precision -----------

// Half vector, its polar cosine and azimuth, and the cosines of a reflection pair.
struct Geometry {
    double h[3], cosH, phiH, cosO, cosI, kh;
    Geometry(const Vec3& wo, const Vec3& wi) {
        double len = 0;
        for (int k = 0; k < 3; ++k) {
            h[k] = double(wo[k]) + wi[k];
            len += h[k] * h[k];
        }
        len = std::sqrt(len);
        for (double& x : h)
            x /= len;
        cosH = h[2];
        phiH = std::atan2(h[1], h[0]);
        cosO = wo.z;
        cosI = wi.z;
        kh = double(wo.x) * h[0] + double(wo.y) * h[1] + double(wo.z) * h[2];
    }
    double tanH2() const { return (1 - cosH * cosH) / (cosH * cosH); }
    double vCavity() const { return std::min({1.0, 2 * cosH * cosO / kh, 2 * cosH * cosI / kh}); }
};

double smithG1(double cosV, double alpha) {
    const double a = cosV / (alpha * std::sqrt(1 - cosV * cosV));
    return 2 / (1 + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(M_PI)));
}

TEST(Formulas, EvalMatchesThePapers) {
    const double e = 20, alpha = 0.3, nu = 40, nv = 5, rs = 0.3, rd = 0.6;
    const auto bl = blinn(float(1 / e), Rgb(1.0f));
    const CookTorrance ct(constantTexture(Rgb(1.0f)), constantTexture(float(alpha)), 1.5f);
    const AshikhminShirley as(constantTexture(Rgb(float(rd))), constantTexture(Rgb(float(rs))),
                              constantTexture(float(nu)), constantTexture(float(nv)), true);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 wo = directionFromDegrees(85 * uniform(11, i, 0), 360 * uniform(11, i, 1));
        const Vec3 wi = directionFromDegrees(85 * uniform(11, i, 2), 360 * uniform(11, i, 3));
        const Geometry g(wo, wi);
        const double fresnel = fresnelDielectric(float(g.kh), 1.5f);
        // Blinn 1977 / Cook & Torrance 1982 with D = (e+2)/(2π) cos^e θh.
        const double dBlinn = (e + 2) / (2 * M_PI) * std::pow(g.cosH, e);
        const double blinnF = dBlinn * g.vCavity() * fresnel / (4 * g.cosO * g.cosI);
        EXPECT_NEAR(bl->eval(kCtx, wo, wi).g, blinnF * g.cosI, 1e-4 * blinnF * g.cosI + 1e-7);
        // Walter et al. 2007 §5.1: Beckmann D, exact Smith G1.
        const double dBeckmann =
            std::exp(-g.tanH2() / (alpha * alpha)) / (M_PI * alpha * alpha * std::pow(g.cosH, 4));
        const double ctF = dBeckmann * smithG1(g.cosO, alpha) * smithG1(g.cosI, alpha) * fresnel /
                           (4 * g.cosO * g.cosI);
        EXPECT_NEAR(ct.eval(kCtx, wo, wi).g, ctF * g.cosI, 1e-4 * ctF * g.cosI + 1e-7);
        // Ashikhmin & Shirley 2000, in their φ form.
        const double exponent =
            nu * std::pow(std::cos(g.phiH), 2) + nv * std::pow(std::sin(g.phiH), 2);
        const double schlick = rs + (1 - rs) * std::pow(1 - g.kh, 5);
        const double specular = std::sqrt((nu + 1) * (nv + 1)) / (8 * M_PI) *
                                std::pow(g.cosH, exponent) / (g.kh * std::max(g.cosO, g.cosI)) *
                                schlick;
        const double diffuse = 28 * rd / (23 * M_PI) * (1 - rs) *
                               (1 - std::pow(1 - g.cosO / 2, 5)) *
                               (1 - std::pow(1 - g.cosI / 2, 5));
        const double asF = (specular + diffuse) * g.cosI;
        EXPECT_NEAR(as.eval(kCtx, wo, wi).g, asF, 1e-4 * asF + 1e-7);
    }
}

// Parameters are textures evaluated at the shading point: a material whose roughness varies
// with u matches the constant material of the roughness at that u.
class RampTexture final : public FloatTexture {
  public:
    float eval(const ShadingContext& ctx) const override { return 0.05f + 0.9f * ctx.uv.x; }
};

TEST(Textures, ParametersAreEvaluatedAtTheShadingPoint) {
    const auto ramp = std::make_shared<RampTexture>();
    const auto white = constantTexture(Rgb(1.0f));
    const Blinn blinnRamp(white, ramp, 1.5f);
    const CookTorrance ctRamp(white, ramp, 1.5f);
    const AshikhminShirley asRamp(white, white, ramp, constantTexture(0.5f), false);
    const Vec3 wo = directionFromDegrees(30, 10), wi = directionFromDegrees(35, 200);
    for (float u : {0.0f, 0.3f, 1.0f}) {
        ShadingContext ctx;
        ctx.uv = Vec2(u, 0.5f);
        const float r = 0.05f + 0.9f * u;
        const Blinn blinnConst(white, constantTexture(r), 1.5f);
        const CookTorrance ctConst(white, constantTexture(r), 1.5f);
        const AshikhminShirley asConst(white, white, constantTexture(r), constantTexture(0.5f),
                                       false);
        EXPECT_EQ(blinnRamp.eval(ctx, wo, wi), blinnConst.eval(kCtx, wo, wi)) << u;
        EXPECT_EQ(blinnRamp.pdf(ctx, wo, wi), blinnConst.pdf(kCtx, wo, wi)) << u;
        EXPECT_EQ(ctRamp.eval(ctx, wo, wi), ctConst.eval(kCtx, wo, wi)) << u;
        EXPECT_EQ(ctRamp.pdf(ctx, wo, wi), ctConst.pdf(kCtx, wo, wi)) << u;
        EXPECT_EQ(asRamp.eval(ctx, wo, wi), asConst.eval(kCtx, wo, wi)) << u;
        EXPECT_EQ(asRamp.pdf(ctx, wo, wi), asConst.pdf(kCtx, wo, wi)) << u;
    }
}

// --- Peaks
// ----------------------------------------------------------------------------------------

// The mirror peak of a narrow lobe is a local maximum of eval: turning it by about half the
// lobe's width in four directions lowers eval (narrow lobes only: for rough ones the cosine
// and Fresnel factors move the maximum of f·cos θi away from the mirror direction).
TEST(Peaks, MirrorPeakIsALocalMaximumOfNarrowLobes) {
    struct Narrow {
        const char* name;
        std::unique_ptr<Material> material;
        double perturbationDegrees;
    };
    Narrow narrow[] = {{"blinn roughness 0.001", blinn(0.001f), 2},
                       {"cook_torrance alpha 0.01", cookTorrance(0.01f), 0.5},
                       {"ashikhmin_shirley 0.001/0.001", ashikhminShirley(0.001f, 0.001f), 2}};
    for (const Narrow& n : narrow)
        for (double theta : {0.0, 30.0, 60.0, 120.0}) {
            const Vec3 wo = directionFromDegrees(theta, 25);
            LobePeaks peaks;
            lobePeakSource(*n.material)->peaks(kCtx, wo, &peaks);
            ASSERT_EQ(peaks.count, 1) << n.name;
            const Vec3 peak = peaks.directions[0];
            EXPECT_EQ(peak, mirrorOf(wo)) << n.name;
            const float atPeak = n.material->eval(kCtx, wo, peak).g;
            const Frame frame(peak);
            for (const Vec3& toward : {frame.s, -frame.s, frame.t, -frame.t}) {
                const Vec3 w = turned(peak, toward, n.perturbationDegrees);
                EXPECT_GT(atPeak, n.material->eval(kCtx, wo, w).g)
                    << n.name << ", wo " << describe(wo) << ", toward " << describe(toward);
            }
        }
}

// Two-stage §2.2: with an exponent ratio above 3, nine more peaks along the cone the lobe
// stretches over. They lie on its ridge: moving across the ridge (along the axis of the large
// exponent) lowers eval. The end peaks (0 and 8) lie on the horizon, where eval is zero.
TEST(Peaks, AshikhminShirleyConePeaksLieOnTheRidge) {
    for (const bool narrowU : {true, false}) {
        const auto m = narrowU ? ashikhminShirley(0.001f, 1.0f) : ashikhminShirley(1.0f, 0.001f);
        const Vec3 across = narrowU ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
        for (double theta : {20.0, 50.0, 130.0}) {
            const Vec3 wo = directionFromDegrees(theta, 35);
            LobePeaks peaks;
            m->peaks(kCtx, wo, &peaks);
            ASSERT_EQ(peaks.count, 10);
            EXPECT_EQ(peaks.directions[0], mirrorOf(wo));
            for (int i = 1; i < 10; ++i) {
                const Vec3 p = peaks.directions[i];
                EXPECT_NEAR(length(p), 1.0f, 1e-5f);
                EXPECT_GE(p.z * wo.z, 0.0f) << "peak on the other side";
                // The cone keeps the mirror direction's component along the narrow axis.
                EXPECT_NEAR(dot(p, across), dot(mirrorOf(wo), across), 1e-6f);
                if (i == 1 || i == 9) continue;  // on the horizon
                const float atPeak = m->eval(kCtx, wo, p).g;
                for (float sign : {1.0f, -1.0f}) {
                    const Vec3 w = normalize(p + across * (sign * 0.05f));
                    EXPECT_GT(atPeak, m->eval(kCtx, wo, w).g)
                        << (narrowU ? "n_u" : "n_v") << " large, wo " << describe(wo) << ", peak "
                        << i - 1;
                }
            }
        }
    }
    // Ratio 3 is not above 3: the mirror direction only.
    const AshikhminShirley mild(constantTexture(Rgb(0.5f)), constantTexture(Rgb(0.5f)),
                                constantTexture(30.0f), constantTexture(10.0f), true);
    LobePeaks peaks;
    mild.peaks(kCtx, directionFromDegrees(30, 0), &peaks);
    EXPECT_EQ(peaks.count, 1);
}

TEST(Lobes, GlossyReflectionOnly) {
    EXPECT_EQ(blinn(0.1f)->lobes(), kReflection | kGlossy);
    EXPECT_EQ(cookTorrance(0.1f)->lobes(), kReflection | kGlossy);
    EXPECT_EQ(ashikhminShirley(0.1f, 0.1f)->lobes(), kReflection | kGlossy | kDiffuse);
    EXPECT_FALSE(blinn(0.1f)->hasTransmission());
}

// --- Negative controls: the χ² runs reject a plausible wrong pdf --------------------------------

// The material's sample() with another pdf().
class WithPdf final : public Material {
  public:
    using Pdf = std::function<float(const Vec3& wo, const Vec3& wi)>;
    WithPdf(const Material& m, Pdf pdf) : m_(m), pdf_(std::move(pdf)) {}
    Rgb eval(const ShadingContext& c, const Vec3& wo, const Vec3& wi) const override {
        return m_.eval(c, wo, wi);
    }
    float pdf(const ShadingContext&, const Vec3& wo, const Vec3& wi) const override {
        return wo.z * wi.z > 0 ? pdf_(wo, wi) : 0.0f;
    }
    bool sample(const ShadingContext& c, const Vec3& wo, float u, Vec2 u2,
                BsdfSample* out) const override {
        return m_.sample(c, wo, u, u2, out);
    }
    uint8_t lobes() const override { return m_.lobes(); }

  private:
    const Material& m_;
    Pdf pdf_;
};

Vec3 halfVectorOf(const Vec3& wo, const Vec3& wi) {
    return normalize(wo + wi);
}

// Half vectors claimed to follow pbrt-v1's cos^e density, (e+1)/(2π) cos^e θh, where Blinn
// samples D·cos θh ∝ cos^(e+1) θh.
TEST(NegativeControls, BlinnRejectsTheCosPowerEDensity) {
    const auto m = blinn(1.0f);
    const float e = 1.0f;
    const WithPdf wrong(*m, [&](const Vec3& wo, const Vec3& wi) {
        const Vec3 h = halfVectorOf(wo, wi);
        return (e + 1) / kTwoPi * std::pow(h.z, e) / (4 * dot(wo, h));
    });
    kChi2.expectRejects(sampleBsdf(wrong, kCtx, kWos[1], 2001).outcome, "Blinn vs cos^e pdf");
}

// The half-vector density D instead of D·cos θh.
TEST(NegativeControls, CookTorranceRejectsTheDensityWithoutCosine) {
    const auto m = cookTorrance(1.0f);
    const WithPdf wrong(*m, [](const Vec3& wo, const Vec3& wi) {
        const Vec3 h = halfVectorOf(wo, wi);
        return beckmannD(h, 1.0f) / (4 * dot(wo, h));
    });
    kChi2.expectRejects(sampleBsdf(wrong, kCtx, kWos[1], 2002).outcome, "Beckmann vs D pdf");
}

// The anisotropic density turned by 90° (u and v exchanged, a tangent-frame mix-up).
TEST(NegativeControls, AshikhminShirleyRejectsExchangedExponents) {
    const auto m = ashikhminShirley(0.001f, 1.0f);
    const auto exchanged = ashikhminShirley(1.0f, 0.001f);
    const WithPdf wrong(
        *m, [&](const Vec3& wo, const Vec3& wi) { return exchanged->pdf(kCtx, wo, wi); });
    kChi2.expectRejects(sampleBsdf(wrong, kCtx, kWos[1], 2003).outcome,
                        "Ashikhmin-Shirley vs exchanged exponents");
}

// --- Declined samples in the shared χ² check --------------------------------------------------

// Lambert declining a fixed fraction of its samples, whatever their direction (uLobe below
// `declined`), with its pdf scaled by `pdfScale`.
class DecliningLambert final : public Material {
  public:
    DecliningLambert(float declined, float pdfScale) : declined_(declined), pdfScale_(pdfScale) {}
    Rgb eval(const ShadingContext& c, const Vec3& wo, const Vec3& wi) const override {
        return lambert_.eval(c, wo, wi);
    }
    float pdf(const ShadingContext& c, const Vec3& wo, const Vec3& wi) const override {
        return pdfScale_ * lambert_.pdf(c, wo, wi);
    }
    bool sample(const ShadingContext& c, const Vec3& wo, float u, Vec2 u2,
                BsdfSample* out) const override {
        return u >= declined_ && lambert_.sample(c, wo, u, u2, out);
    }
    uint8_t lobes() const override { return lambert_.lobes(); }

  private:
    Lambert lambert_{Rgb(0.5f)};
    float declined_, pdfScale_;
};

// The microfacet samplers decline (half vectors that reflect below the surface) and their
// pdf integrates to one minus the probability of declining: sampleBsdf() counts declines in
// the last cell against the missing mass. A sampler whose pdf has that mass fits; one whose
// pdf still integrates to one is rejected.
TEST(DeclinedSamples, CountAgainstTheMassThePdfLacks) {
    const Vec3 wo = directionFromDegrees(40, 30);
    const BsdfSamplingRun fits = sampleBsdf(DecliningLambert(0.05f, 0.95f), kCtx, wo, 3001);
    EXPECT_NEAR(fits.declined, 50000, 1000);
    kChi2.expectFits(fits.outcome, "5 % declined, pdf scaled by 0.95");
    kChi2.expectRejects(sampleBsdf(DecliningLambert(0.05f, 1.0f), kCtx, wo, 3002).outcome,
                        "5 % declined, pdf integrating to one");
}

// --- JSON ---------------------------------------------------------------------------------------

std::string errorPointer(const std::string& text) {
    try {
        materialFromJson(text);
    } catch (const ConfigError& e) {
        return e.pointer();
    }
    return "<no error>";
}

TEST(Json, KeysBuildTheDocumentedMaterials) {
    const Vec3 wo = directionFromDegrees(30, 10), wi = directionFromDegrees(40, 170);
    const auto b = materialFromJson(R"({"type": "blinn", "reflectance": 0.8, "roughness": 0.02,
                                "ior": 1.7})");
    const Blinn bRef(constantTexture(Rgb(0.8f)), constantTexture(0.02f), 1.7f);
    EXPECT_EQ(b->eval(kCtx, wo, wi), bRef.eval(kCtx, wo, wi));
    EXPECT_FLOAT_EQ(bRef.exponent(kCtx), 50.0f);  // two-stage fig. 8: roughness 0.02
    const auto bDefault = materialFromJson(R"({"type": "blinn"})");
    const Blinn bDefaultRef(constantTexture(Rgb(1.0f)), constantTexture(0.1f), 1.5f);
    EXPECT_EQ(bDefault->eval(kCtx, wo, wi), bDefaultRef.eval(kCtx, wo, wi));

    const auto ct = materialFromJson(R"({"type": "cook_torrance", "roughness": 2})");
    const CookTorrance ctRef(constantTexture(Rgb(1.0f)), constantTexture(2.0f), 1.5f);
    EXPECT_EQ(ct->eval(kCtx, wo, wi), ctRef.eval(kCtx, wo, wi));
    const auto ctDefault = materialFromJson(R"({"type": "cook_torrance"})");
    const CookTorrance ctDefaultRef(constantTexture(Rgb(1.0f)), constantTexture(0.2f), 1.5f);
    EXPECT_EQ(ctDefault->eval(kCtx, wo, wi), ctDefaultRef.eval(kCtx, wo, wi));

    const auto asRoughness = materialFromJson(R"({"type": "ashikhmin_shirley", "diffuse": 0.3,
        "specular": [0.2, 0.3, 0.4], "roughness_u": 0.001, "roughness_v": 0.5})");
    const auto asExponents = materialFromJson(R"({"type": "ashikhmin_shirley", "diffuse": 0.3,
        "specular": [0.2, 0.3, 0.4], "exponent_u": 1000, "exponent_v": 2})");
    const auto asDefaults = materialFromJson(R"({"type": "ashikhmin_shirley", "exponent_u": 1000,
        "exponent_v": 2})");
    const AshikhminShirley asRef(constantTexture(Rgb(0.5f)), constantTexture(Rgb(0.5f)),
                                 constantTexture(1000.0f), constantTexture(2.0f), true);
    for (const Vec3& w : {wi, mirrorOf(wo), directionFromDegrees(31, 185)}) {
        const Rgb a = asRoughness->eval(kCtx, wo, w), b2 = asExponents->eval(kCtx, wo, w);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(a[ch], b2[ch], 1e-5f * b2[ch]);
        EXPECT_EQ(asDefaults->eval(kCtx, wo, w), asRef.eval(kCtx, wo, w));
    }
}

TEST(Json, BadKeysNameTheirPointer) {
    const char* as = R"({"type": "ashikhmin_shirley", )";
    EXPECT_EQ(errorPointer(R"({"type": "blinn", "roughness": 0})"), "/materials/m/roughness");
    EXPECT_EQ(errorPointer(R"({"type": "blinn", "roughness": 1.5})"), "/materials/m/roughness");
    EXPECT_EQ(errorPointer(R"({"type": "blinn", "ior": 0})"), "/materials/m/ior");
    EXPECT_EQ(errorPointer(R"({"type": "blinn", "exponent": 10})"), "/materials/m/exponent");
    EXPECT_EQ(errorPointer(R"({"type": "cook_torrance", "roughness": 2.5})"),
              "/materials/m/roughness");
    EXPECT_EQ(errorPointer(R"({"type": "cook_torrance", "reflectance": 1.2})"),
              "/materials/m/reflectance");
    EXPECT_EQ(errorPointer(std::string(as) + R"("roughness_u": 0.1, "exponent_v": 3})"),
              "/materials/m/exponent_v");
    EXPECT_EQ(errorPointer(std::string(as) + R"("diffuse": 0.5})"), "/materials/m/roughness_u");
    EXPECT_EQ(errorPointer(std::string(as) + R"("roughness_u": 0.1})"), "/materials/m/roughness_v");
    EXPECT_EQ(errorPointer(std::string(as) + R"("exponent_u": -1, "exponent_v": 3})"),
              "/materials/m/exponent_u");
    EXPECT_EQ(errorPointer(std::string(as) + R"("roughness_u": 2, "roughness_v": 0.5})"),
              "/materials/m/roughness_u");
    EXPECT_EQ(errorPointer(std::string(as) + R"("exponent_u": 1, "exponent_v": 1,
                                               "specular": 1.5})"),
              "/materials/m/specular");
}

}  // namespace
}  // namespace rr::test
