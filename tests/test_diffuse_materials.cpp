// Tests of the non-microfacet materials (scene/materials/{oren_nayar,phong,lafortune,mix,
// checker}): through the shared BSDF checks (support/bsdf_checks.h) at four incident
// directions including a grazing one and one below the surface, at extreme parameters —
// χ² of sample() against pdf(), weight = eval/pdf and finite, directional albedo ≤ 1 + 1 %,
// reciprocity — with a negative control per family; then each model against an independent
// form of its formula, its peaks, and the loader's rules (references between materials,
// energy checks, errors naming the JSON pointer).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <iterator>
#include <memory>
#include <string>

#include "loader/scene_loader.h"
#include "scene/materials/checker.h"
#include "scene/materials/dielectric.h"
#include "scene/materials/lafortune.h"
#include "scene/materials/lambert.h"
#include "scene/materials/mirror.h"
#include "scene/materials/mix.h"
#include "scene/materials/oren_nayar.h"
#include "scene/materials/phong.h"
#include "scene/textures/checker.h"
#include "support/bsdf_checks.h"
#include "support/chi2.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

// Every χ² run in this file: 8 material configurations × 4 incident directions, and one
// negative control for each of the 4 families (Oren–Nayar, Phong, Lafortune, mix).
constexpr int kRuns = 36;
const Chi2Family kChi2(kRuns);
// Every z-test in this file: Lafortune's tabulated albedo against a Monte Carlo estimate,
// 3 channels × 4 incident directions.
constexpr int kZTests = 12;
const double kZ = zThreshold(sidakAlpha(0.01, kZTests));
constexpr int kSamples = 1000000;
constexpr int kAlbedoSamples = 100000;

const ShadingContext kCtx{};

// Normal incidence, 45° on the far side of the surface (the materials are two-sided),
// oblique, and grazing.
const Vec3 kWos[] = {directionFromDegrees(0, 0), directionFromDegrees(135, 40),
                     directionFromDegrees(70, 200), directionFromDegrees(88, -70)};

TexturePtr<Rgb> colour(float r, float g, float b) {
    return constantTexture(Rgb(r, g, b));
}
TexturePtr<Rgb> grey(float v) {
    return constantTexture(Rgb(v));
}
TexturePtr<float> scalar(float v) {
    return constantTexture(v);
}

Vec3 mirrorOf(const Vec3& wo) {
    return Vec3(-wo.x, -wo.y, wo.z);
}

using Layout = std::function<BsdfHistogramLayout(const Vec3& wo)>;
const Layout kWholeSphere = [](const Vec3&) { return BsdfHistogramLayout{}; };

// A cap of `degrees` around the direction `peak(wo)`, to resolve a sharp lobe.
Layout capAround(std::function<Vec3(const Vec3&)> peak, double degrees) {
    return [peak = std::move(peak), degrees](const Vec3& wo) {
        BsdfHistogramLayout layout;
        layout.axis = peak(wo);
        layout.capDegrees = degrees;
        layout.zCells = 20;
        layout.phiCells = 24;
        return layout;
    };
}

// The shared checks at every incident direction of kWos (4 χ² runs).
void checkMaterial(const Material& m, const std::string& name, uint64_t seed,
                   const Layout& layout = kWholeSphere) {
    for (size_t k = 0; k < std::size(kWos); ++k) {
        const Vec3 wo = kWos[k];
        const std::string where = name + ", wo = " + describe(wo);
        const BsdfSamplingRun run = sampleBsdf(m, kCtx, wo, seed + k, kSamples, layout(wo));
        EXPECT_EQ(run.nonFinite, 0) << where;
        EXPECT_EQ(run.specular, 0) << where;
        EXPECT_EQ(run.weightMismatches, 0) << where << ": " << run.firstMismatch;
        kChi2.expectFits(run.outcome, where);
        const Rgb albedo = directionalAlbedo(m, kCtx, wo, seed + 100 + k, kAlbedoSamples);
        std::printf("[albedo] %s: (%.4f, %.4f, %.4f); %.2f %% of draws declined\n", where.c_str(),
                    albedo.r, albedo.g, albedo.b, 100.0 * run.declined / kSamples);
        EXPECT_TRUE(albedo.isFinite()) << where;
        EXPECT_LE(albedo.maxComponent(), 1.01f) << where;
    }
    const double reciprocity = reciprocityError(m, kCtx, seed + 200);
    std::printf("[reciprocity] %s: largest relative error %.2e\n", name.c_str(), reciprocity);
    EXPECT_LT(reciprocity, 1e-3) << name;
}

// Negative controls: samples from `sampler` judged against the density `claimed` states.
class Impostor final : public Material {
  public:
    Impostor(const Material& sampler, const Material& claimed)
        : sampler_(sampler), claimed_(claimed) {}
    Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override {
        return claimed_.eval(ctx, wo, wi);
    }
    float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const override {
        return claimed_.pdf(ctx, wo, wi);
    }
    bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                BsdfSample* out) const override {
        return sampler_.sample(ctx, wo, uLobe, uDirection, out);
    }
    uint8_t lobes() const override { return claimed_.lobes(); }

  private:
    const Material& sampler_;
    const Material& claimed_;
};

void expectRejected(const Material& sampler, const Material& claimed, const Vec3& wo, uint64_t seed,
                    const std::string& what, const BsdfHistogramLayout& layout = {}) {
    const Impostor impostor(sampler, claimed);
    kChi2.expectRejects(sampleBsdf(impostor, kCtx, wo, seed, kSamples, layout).outcome, what);
}

// A random direction pair on one side of the surface (the lower side for odd i).
std::pair<Vec3, Vec3> randomPair(uint64_t seed, int i) {
    auto direction = [&](uint64_t dim) {
        const double z = uniform(seed, i, dim), phi = 2 * M_PI * uniform(seed, i, dim + 1);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        const float side = i % 2 ? -1.0f : 1.0f;
        return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), side * float(z));
    };
    return {direction(0), direction(2)};
}

double relativeError(double a, double b) {
    return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-12});
}

// --- Oren–Nayar -------------------------------------------------------------------------------

TEST(OrenNayarSampling, SigmaZero) {
    checkMaterial(OrenNayar(colour(0.5f, 0.6f, 0.7f), scalar(0)), "Oren–Nayar σ = 0°", 1000);
}

TEST(OrenNayarSampling, SigmaNinety) {
    checkMaterial(OrenNayar(colour(0.9f, 1.0f, 0.8f), scalar(90)), "Oren–Nayar σ = 90°", 1010);
}

TEST(OrenNayarNegativeControl, CosineSamplesRejectAUniformHemisphere) {
    const OrenNayar m(grey(0.8f), scalar(90));
    const Phong uniformHemisphere(grey(0), grey(1), scalar(0));  // at normal incidence
    expectRejected(m, uniformHemisphere, Vec3(0, 0, 1), 1020,
                   "Oren–Nayar samples vs a uniform-hemisphere pdf");
}

TEST(OrenNayar, SigmaZeroIsLambert) {
    const OrenNayar on(colour(0.3f, 0.5f, 0.9f), scalar(0));
    const Lambert lambert(Rgb(0.3f, 0.5f, 0.9f));
    for (int i = 0; i < 10000; ++i) {
        const auto [wo, wi] = randomPair(1030, i);
        const Rgb a = on.eval(kCtx, wo, wi), b = lambert.eval(kCtx, wo, wi);
        for (int c = 0; c < 3; ++c)
            ASSERT_NEAR(a[c], b[c], 1e-6f * b[c]) << describe(wo) << " " << describe(wi);
        ASSERT_EQ(on.pdf(kCtx, wo, wi), lambert.pdf(kCtx, wo, wi));
        BsdfSample s, t;
        const Vec2 u = uniform2(1031, i);
        ASSERT_EQ(on.sample(kCtx, wo, 0.5f, u, &s), lambert.sample(kCtx, wo, 0.5f, u, &t));
        EXPECT_EQ(s.wi, t.wi);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(s.weight[c], t.weight[c], 1e-6f);
    }
}

// Oren & Nayar 1994 eq. 30 with the angles computed by trigonometry, in double: the
// implementation's trigonometry-free form must agree.
TEST(OrenNayar, MatchesTheAngleFormOfTheModel) {
    const double sigmaDegrees = 30, rho = 0.7;
    const OrenNayar m(grey(float(rho)), scalar(float(sigmaDegrees)));
    const double s2 = std::pow(sigmaDegrees * M_PI / 180, 2);
    const double a = 1 - 0.5 * s2 / (s2 + 0.33), b = 0.45 * s2 / (s2 + 0.09);
    for (int i = 0; i < 10000; ++i) {
        const auto [wo, wi] = randomPair(1040, i);
        const double thetaI = std::acos(std::abs(double(wi.z)));
        const double thetaO = std::acos(std::abs(double(wo.z)));
        const double dPhi = std::atan2(wi.y, wi.x) - std::atan2(wo.y, wo.x);
        const double alpha = std::max(thetaI, thetaO), beta = std::min(thetaI, thetaO);
        const double f =
            rho / M_PI * (a + b * std::max(0.0, std::cos(dPhi)) * std::sin(alpha) * std::tan(beta));
        ASSERT_LT(relativeError(m.eval(kCtx, wo, wi).g, f * std::cos(thetaI)), 1e-4)
            << describe(wo) << " " << describe(wi);
    }
}

TEST(OrenNayar, PeaksAreRetroReflectionAndTheNormal) {
    const OrenNayar m(grey(0.5f), scalar(20));
    for (const Vec3& wo : kWos) {
        LobePeaks peaks;
        m.peaks(kCtx, wo, &peaks);
        ASSERT_EQ(peaks.count, 2);
        EXPECT_EQ(peaks.directions[0], wo);
        EXPECT_EQ(peaks.directions[1], Vec3(0, 0, wo.z < 0 ? -1.0f : 1.0f));
    }
    EXPECT_EQ(m.lobes(), kReflection | kDiffuse);
}

// --- Phong --------------------------------------------------------------------------------------

TEST(PhongSampling, ExponentZero) {
    checkMaterial(Phong(grey(0.3f), grey(0.7f), scalar(0)), "Phong n = 0", 2000);
}

TEST(PhongSampling, ExponentOne) {
    checkMaterial(Phong(colour(0.2f, 0.3f, 0.1f), colour(0.7f, 0.6f, 0.5f), scalar(1)),
                  "Phong n = 1", 2010);
}

// The lobe's width is about 1/√n = 0.6°: a 3° cap around the mirror direction resolves it.
TEST(PhongSampling, ExponentTenThousandZoomedOnTheMirrorDirection) {
    checkMaterial(Phong(grey(0.2f), grey(0.8f), scalar(10000)), "Phong n = 10⁴", 2020,
                  capAround(mirrorOf, 3));
}

// An exponent 15 % off is told apart within a 20° cap around the mirror direction.
TEST(PhongNegativeControl, LobeSamplesRejectAWiderExponent) {
    const Phong sampled(grey(0), grey(1), scalar(100)), claimed(grey(0), grey(1), scalar(115));
    const Vec3 wo = directionFromDegrees(45, 10);
    expectRejected(sampled, claimed, wo, 2030, "Phong n = 100 samples vs the n = 115 pdf",
                   capAround(mirrorOf, 20)(wo));
}

// Lafortune & Willems 1994 eq. 4 with α from acos, in double.
TEST(Phong, MatchesTheAngleFormOfTheModel) {
    const double kd = 0.25, ks = 0.6, n = 20;
    const Phong m(grey(float(kd)), grey(float(ks)), scalar(float(n)));
    for (int i = 0; i < 10000; ++i) {
        const auto [wo, wi] = randomPair(2040, i);
        const Vec3 r = mirrorOf(wo);
        const double cosAlpha = double(wi.x) * r.x + double(wi.y) * r.y + double(wi.z) * r.z;
        const double lobe = cosAlpha > 0 ? (n + 2) / (2 * M_PI) * std::pow(cosAlpha, n) : 0;
        const double f = kd / M_PI + ks * lobe;
        ASSERT_LT(relativeError(m.eval(kCtx, wo, wi).r, f * std::abs(wi.z)), 1e-4)
            << describe(wo) << " " << describe(wi);
    }
}

// At normal incidence the normalisation is exact: ∫ f cos θ dω = kd + ks (midpoint rule).
TEST(Phong, AlbedoAtNormalIncidenceIsDiffusePlusSpecular) {
    for (const float n : {0.0f, 1.0f, 10.0f}) {
        const Phong m(grey(0.3f), grey(0.6f), scalar(n));
        double albedo = 0, probability = 0;
        const int nz = 4000, nphi = 16;
        for (int i = 0; i < nz; ++i)
            for (int j = 0; j < nphi; ++j) {
                const double z = (i + 0.5) / nz, phi = (j + 0.5) * 2 * M_PI / nphi;
                const double r = std::sqrt(1 - z * z);
                const Vec3 wi(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                albedo += m.eval(kCtx, Vec3(0, 0, 1), wi).r;
                probability += m.pdf(kCtx, Vec3(0, 0, 1), wi);
            }
        const double dOmega = (1.0 / nz) * (2 * M_PI / nphi);
        EXPECT_NEAR(albedo * dOmega, 0.9, 1e-4) << "n = " << n;
        EXPECT_NEAR(probability * dOmega, 1.0, 1e-4) << "n = " << n;
    }
}

TEST(Phong, PeakIsTheMirrorDirection) {
    const Phong m(grey(0.3f), grey(0.6f), scalar(30));
    for (const Vec3& wo : kWos) {
        LobePeaks peaks;
        m.peaks(kCtx, wo, &peaks);
        ASSERT_EQ(peaks.count, 1);
        EXPECT_EQ(peaks.directions[0], mirrorOf(wo));
    }
}

TEST(Phong, BlackMaterialDeclinesEverySample) {
    const Phong m(grey(0), grey(0), scalar(10));
    BsdfSample s;
    EXPECT_FALSE(m.sample(kCtx, kWos[1], 0.5f, Vec2(0.3f, 0.3f), &s));
    EXPECT_EQ(m.pdf(kCtx, kWos[1], mirrorOf(kWos[1])), 0.0f);
}

// --- Lafortune ----------------------------------------------------------------------------------

LafortuneLobe mirrorLobe(float exponent, float albedoAtNormalIncidence) {
    // Cx = Cy = −Cz = −1: the lobe cos^n α around the mirror direction, whose albedo at
    // normal incidence is ρ·2π/(n + 2).
    const float rho = albedoAtNormalIncidence * (exponent + 2) / (2 * kPi);
    return {Vec3(-1, -1, 1), exponent, Rgb(rho)};
}

TEST(LafortuneSampling, SkinPreset) {
    checkMaterial(Lafortune(constantTexture(Lafortune::skinDiffuse()), Lafortune::skinLobes()),
                  "Lafortune skin", 3000);
}

// n = 2000: about 1.3° wide; a 6° cap around the lobe axis. At the grazing direction the
// lobe straddles the horizon, and sample() declines the draws below it.
TEST(LafortuneSampling, SharpLobeZoomedOnItsAxis) {
    const Lafortune m(grey(0.1f), {mirrorLobe(2000, 0.8f)});
    checkMaterial(m, "Lafortune n = 2000", 3010, capAround(mirrorOf, 6));
}

// Lobe choice probabilities off (the pdf of a brighter diffuse term) are detected.
TEST(LafortuneNegativeControl, SkinSamplesRejectOtherLobeProbabilities) {
    const Lafortune sampled(constantTexture(Lafortune::skinDiffuse()), Lafortune::skinLobes());
    const Lafortune claimed(colour(0.6f, 0.45f, 0.5f), Lafortune::skinLobes());
    expectRejected(sampled, claimed, directionFromDegrees(45, 0), 3020,
                   "Lafortune skin samples vs the pdf with a brighter diffuse term");
}

// A lobe with Cx = Cy = −Cz = −1 and ρ = ks·(n + 2)/(2π) is Phong's specular lobe.
TEST(Lafortune, MirrorLobeIsThePhongLobe) {
    const float n = 25, kd = 0.2f, ks = 0.7f;
    const Lafortune lafortune(grey(kd), {mirrorLobe(n, ks)});
    const Phong phong(grey(kd), grey(ks), scalar(n));
    for (int i = 0; i < 10000; ++i) {
        const auto [wo, wi] = randomPair(3030, i);
        ASSERT_LT(relativeError(lafortune.eval(kCtx, wo, wi).r, phong.eval(kCtx, wo, wi).r), 1e-4)
            << describe(wo) << " " << describe(wi);
    }
    // At normal incidence the lobe probabilities agree too (both are the albedos).
    for (int i = 0; i < 1000; ++i) {
        const Vec3 wi = randomPair(3031, 2 * i).second;
        ASSERT_LT(relativeError(lafortune.pdf(kCtx, Vec3(0, 0, 1), wi),
                                phong.pdf(kCtx, Vec3(0, 0, 1), wi)),
                  1e-3)
            << describe(wi);
    }
}

TEST(Lafortune, IsReciprocalForAnisotropicLobes) {
    const Lafortune m(grey(0.05f), {{Vec3(-0.8f, -0.5f, 0.7f), 8, Rgb(0.5f, 1.0f, 1.5f)},
                                    {Vec3(0.6f, 0.6f, 0.3f), 3, Rgb(0.2f)}});
    EXPECT_LT(reciprocityError(m, kCtx, 3040), 1e-4);
}

// The lobe albedos from the tables (used for lobe selection and the load-time energy check)
// against Monte Carlo estimates from sample(): z-tests with the estimates' standard errors,
// plus the tables' accuracy (10⁻³ relative).
TEST(Lafortune, TabulatedLobeAlbedoMatchesMonteCarlo) {
    const Lafortune m(grey(0), Lafortune::skinLobes());
    const int samples = 400000;
    for (size_t k = 0; k < std::size(kWos); ++k) {
        const Vec3 wo = kWos[k];
        double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
        for (int i = 0; i < samples; ++i) {
            BsdfSample s;
            if (!m.sample(kCtx, wo, uniform(3050 + k, i, 2), uniform2(3050 + k, i), &s)) continue;
            for (int c = 0; c < 3; ++c) {
                sum[c] += s.weight[c];
                sum2[c] += double(s.weight[c]) * s.weight[c];
            }
        }
        const Rgb table = m.lobeAlbedo(wo);
        for (int c = 0; c < 3; ++c) {
            const double mean = sum[c] / samples;
            const double se = std::sqrt((sum2[c] / samples - mean * mean) / (samples - 1));
            const double z = (mean - table[c]) / std::sqrt(se * se + std::pow(1e-3 * table[c], 2));
            std::printf(
                "[z] skin lobe albedo, wo = %s, channel %d: MC %.5f ± %.5f, table %.5f, "
                "z = %.2f\n",
                describe(wo).c_str(), c, mean, se, table[c], z);
            EXPECT_LT(std::abs(z), kZ) << describe(wo) << " channel " << c;
        }
    }
}

TEST(Lafortune, SkinPresetConservesEnergy) {
    const Lafortune m(constantTexture(Lafortune::skinDiffuse()), Lafortune::skinLobes());
    Vec3 where;
    const Rgb lobes = m.maxLobeAlbedo(&where);
    const Rgb total = lobes + Lafortune::skinDiffuse();
    std::printf("[skin] largest directional albedo (%.4f, %.4f, %.4f) at θo = %.1f°\n", total.r,
                total.g, total.b, std::acos(where.z) * 180 / M_PI);
    EXPECT_LE(total.maxComponent(), 1.0f);
    EXPECT_GT(std::min({lobes.r, lobes.g, lobes.b}), 0.0f);
}

TEST(Lafortune, PeaksAreTheLobeAxesAboveTheSurface) {
    const Lafortune mirror(grey(0.1f), {mirrorLobe(30, 0.5f)});
    for (const Vec3& wo : kWos) {
        LobePeaks peaks;
        mirror.peaks(kCtx, wo, &peaks);
        ASSERT_EQ(peaks.count, 1);
        EXPECT_LT(length(peaks.directions[0] - mirrorOf(wo)), 1e-6f) << describe(wo);
    }
    // Skin at normal incidence: lobe 0 (Cx = Cy, Cz < 0) points into the surface; lobes 1
    // and 2 point along the normal, and their three channels share that axis.
    const Lafortune skin(grey(0), Lafortune::skinLobes());
    LobePeaks peaks;
    skin.peaks(kCtx, Vec3(0, 0, 1), &peaks);
    ASSERT_EQ(peaks.count, 1);
    EXPECT_EQ(peaks.directions[0], Vec3(0, 0, 1));
    // Obliquely, each channel of lobes 1 and 2 has its own axis: 6 peaks, all above.
    LobePeaks oblique;
    const Vec3 wo = directionFromDegrees(60, 30);
    skin.peaks(kCtx, wo, &oblique);
    EXPECT_EQ(oblique.count, 6);
    for (int i = 0; i < oblique.count; ++i)
        EXPECT_GT(oblique.directions[i].z, 0.0f);
}

// --- Mix ----------------------------------------------------------------------------------------

TEST(MixSampling, LambertPlusPhong) {
    const Lambert lambert(Rgb(0.8f, 0.7f, 0.6f));
    const Phong phong(grey(0), grey(0.9f), scalar(50));
    checkMaterial(MixMaterial(&lambert, &phong, scalar(0.4f)), "mix 0.4 Lambert + 0.6 Phong", 4000);
}

TEST(MixNegativeControl, SamplesRejectAnotherWeight) {
    const Lambert lambert(Rgb(0.8f));
    const Phong phong(grey(0), grey(0.9f), scalar(50));
    const MixMaterial sampled(&lambert, &phong, scalar(0.4f));
    const MixMaterial claimed(&lambert, &phong, scalar(0.5f));
    expectRejected(sampled, claimed, directionFromDegrees(30, 0), 4010,
                   "mix with weight 0.4 vs the pdf of weight 0.5");
}

TEST(Mix, EvalAndPdfAreTheWeightedSums) {
    const OrenNayar a(grey(0.6f), scalar(30));
    const Phong b(grey(0.2f), grey(0.7f), scalar(12));
    const float w = 0.35f;
    const MixMaterial m(&a, &b, scalar(w));
    for (int i = 0; i < 2000; ++i) {
        const auto [wo, wi] = randomPair(4020, i);
        EXPECT_NEAR(m.eval(kCtx, wo, wi).r,
                    w * a.eval(kCtx, wo, wi).r + (1 - w) * b.eval(kCtx, wo, wi).r, 1e-6f);
        EXPECT_NEAR(m.pdf(kCtx, wo, wi), w * a.pdf(kCtx, wo, wi) + (1 - w) * b.pdf(kCtx, wo, wi),
                    1e-6f);
    }
    LobePeaks peaks;
    m.peaks(kCtx, kWos[2], &peaks);
    EXPECT_EQ(peaks.count, 3);  // Oren–Nayar's two, Phong's one
    EXPECT_EQ(m.lobes(), kReflection | kDiffuse | kGlossy);
}

// A specular child keeps its weight; its probability is scaled by the mixture weight.
TEST(Mix, SpecularChildSampleKeepsItsWeight) {
    const Mirror mirror(Rgb(0.9f, 0.8f, 0.7f));
    const Lambert lambert(Rgb(0.5f));
    const MixMaterial m(&mirror, &lambert, scalar(0.3f));
    BsdfSample s;
    ASSERT_TRUE(m.sample(kCtx, kWos[2], 0.1f, Vec2(0.4f, 0.4f), &s));
    EXPECT_TRUE(s.isSpecular());
    EXPECT_EQ(s.wi, mirrorOf(kWos[2]));
    EXPECT_FLOAT_EQ(s.pdf, 0.3f);
    EXPECT_EQ(s.weight, Rgb(0.9f, 0.8f, 0.7f));
    ASSERT_TRUE(m.sample(kCtx, kWos[2], 0.5f, Vec2(0.4f, 0.4f), &s));
    EXPECT_FALSE(s.isSpecular());
    EXPECT_NEAR(s.pdf, 0.7f * lambert.pdf(kCtx, kWos[2], s.wi), 1e-6f);
    EXPECT_NEAR(s.weight.r, 0.5f, 1e-6f);  // (0.7·f) / (0.7·p)
}

// The child's uLobe is rescaled so that it is uniform on [0, 1) again: a dielectric child at
// weight w reflects for uLobe < w·F, and in the other child's interval uLobe ≥ w maps to
// (uLobe − w)/(1 − w).
TEST(Mix, ChildLobeNumbersAreRescaled) {
    const Dielectric glass(1.5f, Rgb(1.0f), Rgb(1.0f));
    const float w = 0.6f;
    const MixMaterial first(&glass, &glass, scalar(w));
    const Vec3 wo = directionFromDegrees(60, 0);
    const float f = glass.reflectProbability(wo);
    auto reflects = [&](float uLobe) {
        BsdfSample s;
        EXPECT_TRUE(first.sample(kCtx, wo, uLobe, Vec2(0.5f, 0.5f), &s));
        return (s.lobe & kReflection) != 0;
    };
    EXPECT_TRUE(reflects(w * f * 0.99f));
    EXPECT_FALSE(reflects(w * f * 1.01f));
    EXPECT_TRUE(reflects(w + (1 - w) * f * 0.99f));
    EXPECT_FALSE(reflects(w + (1 - w) * f * 1.01f));
    EXPECT_FALSE(reflects(1.0f - 0x1p-24f));
}

// --- Checker material ---------------------------------------------------------------------------

TEST(CheckerMaterial, EachSquareUsesItsMaterial) {
    const Lambert even(Rgb(0.2f));
    const Phong odd(grey(0.1f), grey(0.5f), scalar(10));
    const CheckerMaterial m(&even, &odd, Checkerboard{4, 2});
    const Vec3 wo = kWos[2], wi = directionFromDegrees(30, 120);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 2; ++j) {
            const ShadingContext ctx{Vec2((i + 0.5f) / 4, (j + 0.5f) / 2), Vec3(0.0f)};
            const Material& expected = (i + j) % 2 == 0 ? static_cast<const Material&>(even) : odd;
            EXPECT_EQ(m.eval(ctx, wo, wi), expected.eval(ctx, wo, wi)) << i << ", " << j;
            EXPECT_EQ(m.pdf(ctx, wo, wi), expected.pdf(ctx, wo, wi));
            LobePeaks a, b;
            m.peaks(ctx, wo, &a);
            lobePeakSource(expected)->peaks(ctx, wo, &b);
            EXPECT_EQ(a.count, b.count);
        }
    EXPECT_EQ(m.lobes(), kReflection | kDiffuse | kGlossy);
}

// Lambert's albedo is a texture: a checker of two greys.
TEST(LambertTexture, AlbedoFollowsTheTexture) {
    const Lambert m(
        std::make_shared<CheckerTexture<Rgb>>(grey(0.2f), grey(0.6f), Checkerboard{2, 2}));
    const Vec3 wo(0, 0, 1);
    BsdfSample s;
    ASSERT_TRUE(m.sample({Vec2(0.25f, 0.25f), Vec3(0.0f)}, wo, 0.5f, Vec2(0.3f, 0.3f), &s));
    EXPECT_EQ(s.weight, Rgb(0.2f));
    ASSERT_TRUE(m.sample({Vec2(0.75f, 0.25f), Vec3(0.0f)}, wo, 0.5f, Vec2(0.3f, 0.3f), &s));
    EXPECT_EQ(s.weight, Rgb(0.6f));
}

// --- Loader -------------------------------------------------------------------------------------

// Loads a one-quad scene with the given material table (the quad uses "m"); returns the
// pointer of the ConfigError, or "<no error>".
std::string loadError(const Json& materials) {
    Json scene = {{"render", {{"resolution", {4, 4}}, {"spp", 1}}},
                  {"camera", {{"position", {0, 0, 3}}, {"look_at", {0, 0, 0}}}},
                  {"materials", materials},
                  {"shapes",
                   {{{"type", "quad"},
                     {"corner", {-1, -1, 0}},
                     {"edge_u", {2, 0, 0}},
                     {"edge_v", {0, 2, 0}},
                     {"material", "m"}}}},
                  {"lights", {{{"type", "point"}, {"position", {0, 0, 2}}, {"intensity", 1}}}}};
    try {
        loadScene(scene, AssetResolver({}));
    } catch (const ConfigError& e) {
        EXPECT_NE(std::string(e.what()).find(e.pointer()), std::string::npos) << e.what();
        return e.pointer();
    }
    return "<no error>";
}

TEST(MaterialLoader, EveryNewTypeLoadsWithItsDefaults) {
    for (const char* type : {"oren_nayar", "phong"})
        EXPECT_EQ(loadError({{"m", {{"type", type}}}}), "<no error>") << type;
    EXPECT_EQ(loadError({{"m", {{"type", "lafortune"}, {"preset", "skin"}}}}), "<no error>");
    EXPECT_EQ(loadError({{"m",
                          {{"type", "lafortune"},
                           {"diffuse", 0.2},
                           {"lobes", {{{"c", {-1, -1, 1}}, {"exponent", 20}, {"albedo", 2}}}}}}}),
              "<no error>");
    EXPECT_EQ(loadError({{"m", {{"type", "mix"}, {"materials", {"a", {{"type", "lambert"}}}}}},
                         {"a", {{"type", "phong"}, {"diffuse", 0.3}}}}),
              "<no error>");
    EXPECT_EQ(loadError({{"m",
                          {{"type", "checker"},
                           {"even", {{"type", "lambert"}, {"albedo", 0.2}}},
                           {"odd", "b"},
                           {"squares", {4, 4}}}},
                         {"b", {{"type", "mirror"}}}}),
              "<no error>");
}

TEST(MaterialLoader, ReferencesResolveInAnyOrderButNotInCycles) {
    // "m" is built before "z1" and "z2" (the table is read in key order) and refers to them.
    EXPECT_EQ(loadError({{"m", {{"type", "mix"}, {"materials", {"z1", "z2"}}}},
                         {"z1", {{"type", "checker"}, {"even", "z2"}, {"odd", "z2"}}},
                         {"z2", {{"type", "oren_nayar"}}}}),
              "<no error>");
    EXPECT_EQ(loadError({{"m", {{"type", "mix"}, {"materials", {"m", "m"}}}}}),
              "/materials/m/materials/0");
    EXPECT_EQ(
        loadError({{"m", {{"type", "mix"}, {"materials", {"n", {{"type", "lambert"}}}}}},
                   {"n", {{"type", "checker"}, {"even", {{"type", "lambert"}}}, {"odd", "m"}}}}),
        "/materials/n/odd");
    EXPECT_EQ(loadError({{"m", {{"type", "mix"}, {"materials", {"nope", "nope"}}}}}),
              "/materials/m/materials/0");
    EXPECT_EQ(loadError({{"m", {{"type", "mix"}, {"materials", {{{"type", "lambert"}}, 3}}}}}),
              "/materials/m/materials/1");
    EXPECT_EQ(loadError({{"m", {{"type", "mix"}, {"materials", {"m"}}}}}),
              "/materials/m/materials");
    EXPECT_EQ(loadError({{"m", {{"type", "checker"}, {"even", {{"type", "lambert"}}}}}}),
              "/materials/m/odd");
    // Unreferenced entries are loaded, and checked, too.
    EXPECT_EQ(loadError({{"m", {{"type", "lambert"}}}, {"unused", {{"type", "lambret"}}}}),
              "/materials/unused/type");
}

TEST(MaterialLoader, ImpossibleParametersNameTheirPointer) {
    EXPECT_EQ(loadError({{"m", {{"type", "oren_nayar"}, {"sigma", 95}}}}), "/materials/m/sigma");
    EXPECT_EQ(loadError({{"m", {{"type", "phong"}, {"exponent", -1}}}}), "/materials/m/exponent");
    EXPECT_EQ(loadError({{"m", {{"type", "mix"}, {"materials", {"m2", "m2"}}, {"weight", 1.5}}},
                         {"m2", {{"type", "lambert"}}}}),
              "/materials/m/weight");
    EXPECT_EQ(loadError({{"m",
                          {{"type", "lambert"},
                           {"albedo", {{"type", "gradient"}, {"from", 0}, {"to", 1.2}}}}}}),
              "/materials/m/albedo/to");
}

// Phong: kd + ks ≤ 1 when both are constants (a textured part cannot be checked at load).
TEST(MaterialLoader, PhongMustConserveEnergy) {
    EXPECT_EQ(loadError({{"m", {{"type", "phong"}, {"diffuse", 0.5}, {"specular", 0.5}}}}),
              "<no error>");
    EXPECT_EQ(
        loadError(
            {{"m",
              {{"type", "phong"}, {"diffuse", {0.5, 0.2, 0.2}}, {"specular", {0.6, 0.2, 0.2}}}}}),
        "/materials/m/specular");
    EXPECT_EQ(loadError({{"m",
                          {{"type", "phong"},
                           {"diffuse", {{"type", "gradient"}, {"from", 0}, {"to", 0.9}}},
                           {"specular", 0.5}}}}),
              "<no error>");
}

// Lafortune lobes are not normalised: a lobe (plus a constant diffuse term) whose directional
// albedo exceeds 1 somewhere is rejected.
TEST(MaterialLoader, LafortuneMustConserveEnergy) {
    // ρ·2π/(n + 2) at normal incidence: 2·2π/22 = 0.57, 4·2π/22 = 1.14.
    auto lafortune = [](double rho, double diffuse) {
        return Json{{"m",
                     {{"type", "lafortune"},
                      {"diffuse", diffuse},
                      {"lobes", {{{"c", {-1, -1, 1}}, {"exponent", 20}, {"albedo", rho}}}}}}};
    };
    EXPECT_EQ(loadError(lafortune(2, 0.4)), "<no error>");
    EXPECT_EQ(loadError(lafortune(2, 0.5)), "/materials/m/lobes");
    EXPECT_EQ(loadError(lafortune(4, 0)), "/materials/m/lobes");
    // A retro-reflective lobe that grows towards grazing (|C| > 1 there).
    EXPECT_EQ(
        loadError({{"m",
                    {{"type", "lafortune"},
                     {"lobes", {{{"c", {1.5, 1.5, 0.5}}, {"exponent", 4}, {"albedo", 1}}}}}}}),
        "/materials/m/lobes");
    EXPECT_EQ(loadError({{"m", {{"type", "lafortune"}, {"preset", "skin"}, {"diffuse", 0.9}}}}),
              "/materials/m/preset");
    EXPECT_EQ(loadError({{"m", {{"type", "lafortune"}, {"preset", "velvet"}}}}),
              "/materials/m/preset");
    EXPECT_EQ(loadError({{"m",
                          {{"type", "lafortune"},
                           {"preset", "skin"},
                           {"lobes", {{{"c", {-1, -1, 1}}, {"exponent", 2}}}}}}}),
              "/materials/m/lobes");
    EXPECT_EQ(loadError({{"m", {{"type", "lafortune"}, {"lobes", Json::array()}}}}),
              "/materials/m/lobes");
    EXPECT_EQ(loadError({{"m", {{"type", "lafortune"}, {"lobes", {{{"c", {-1, -1, 1}}}}}}}}),
              "/materials/m/lobes/0/exponent");
}

}  // namespace
}  // namespace rr::test
