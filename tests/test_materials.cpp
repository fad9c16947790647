// Tests of the materials (scene/materials/*): χ² of Lambert's sampled directions against its
// pdf (both sides), sample weights against eval/pdf, reciprocity and energy, and the specular
// Mirror and Dielectric: Fresnel (against an independent angle form), Snell's law, the reflect
// / transmit choice, weights and peaks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "sampling/hash.h"
#include "sampling/warps.h"
#include "scene/materials/dielectric.h"
#include "scene/materials/lambert.h"
#include "scene/materials/mirror.h"
#include "support/bsdf_checks.h"
#include "support/chi2.h"
#include "support/histograms.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

// Every χ² run in this file: Lambert at 4 outgoing directions, 2 negative controls, and
// Lambert through the shared BSDF checks on the whole sphere and on a zoomed cap.
constexpr int kRuns = 8;
const Chi2Family kChi2(kRuns);
const double kAlpha = kChi2.alpha();
// Every z-test in this file: reflection fraction at 5 incident angles, and 1 negative control.
constexpr int kZTests = 6;
const double kZ = zThreshold(sidakAlpha(0.01, kZTests));
constexpr int kSamples = 1000000;

const ShadingContext kCtx{};

// Outgoing directions: normal, oblique, grazing, and below the surface (two-sided Lambert).
const Vec3 kWos[] = {Vec3(0, 0, 1), directionFromDegrees(50, 30), directionFromDegrees(89, 200),
                     directionFromDegrees(120, -60)};

// --- Lambert ----------------------------------------------------------------------------------

// Lambert sample() directions for `wo` histogrammed over the whole sphere (41 z-cells: the
// horizon z = 0 is in the middle of a cell) against `pdf`.
// sample() may decline only where the cosine-weighted direction is on the horizon: u on the
// edge of the square (u = 0 has probability 2^-24 per coordinate) maps to the rim of the disk,
// where cos θ = 0 and so does the pdf (float rounding of 1 − x² − y² reaches the horizon at a
// rate of ~6e-8). Any other decline is a failure.
struct LambertRun {
    Chi2Outcome outcome;
    int declined = 0;    // all declines
    int offHorizon = 0;  // declines for a disk point not on the rim (to 1e-6)
};
LambertRun lambertChi2(const Vec3& wo, uint64_t seed,
                       const std::function<double(const Vec3&)>& pdf) {
    const Lambert m(Rgb(0.5f, 0.6f, 0.7f));
    DirectionHistogram h(41, 60);
    LambertRun run;
    for (int i = 0; i < kSamples; ++i) {
        BsdfSample s;
        const Vec2 u = uniform2(seed, i);
        if (!m.sample(kCtx, wo, uniform(seed, i, 2), u, &s)) {
            ++run.declined;
            const Vec2 d = squareToUniformDisk(u);
            run.offHorizon += double(d.x) * d.x + double(d.y) * d.y < 1 - 1e-6;
            continue;
        }
        h.add(s.wi);
    }
    run.outcome = chi2GoodnessOfFit(h.counts(), h.expected(pdf, kSamples - run.declined));
    return run;
}

class LambertChi2 : public ::testing::TestWithParam<Vec3> {};

TEST_P(LambertChi2, SampledDirectionsFollowPdf) {
    const Lambert m(Rgb(0.5f, 0.6f, 0.7f));
    const Vec3 wo = GetParam();
    const LambertRun run = lambertChi2(wo, 100 + uint64_t(std::abs(wo.x) * 1000),
                                       [&](const Vec3& wi) { return m.pdf(kCtx, wo, wi); });
    EXPECT_EQ(run.offHorizon, 0) << "sample() declined directions above the horizon";
    EXPECT_LE(run.declined, 10) << "declined samples: expected ~0.1 per 10^6";
    if (run.declined > 0)
        std::printf("[info] %d of %d samples declined on the horizon\n", run.declined, kSamples);
    kChi2.expectFits(run.outcome, "Lambert, wo = " + describe(wo));
}

INSTANTIATE_TEST_SUITE_P(OutgoingDirections, LambertChi2, ::testing::ValuesIn(kWos));

TEST(LambertChi2NegativeControl, SamplesBelowRejectThePdfAbove) {
    const Lambert m(Rgb(0.5f));
    const Vec3 wo = directionFromDegrees(120, -60);
    const LambertRun run = lambertChi2(
        wo, 200, [&](const Vec3& wi) { return m.pdf(kCtx, Vec3(wo.x, wo.y, -wo.z), wi); });
    kChi2.expectRejects(run.outcome, "Lambert below vs pdf above");
}

TEST(LambertChi2NegativeControl, SamplesRejectUniformHemispherePdf) {
    const Vec3 wo = directionFromDegrees(50, 30);
    const LambertRun run =
        lambertChi2(wo, 201, [](const Vec3& wi) { return wi.z > 0 ? 0.5 / M_PI : 0.0; });
    kChi2.expectRejects(run.outcome, "Lambert vs uniform hemisphere");
}

// The shared checks (support/bsdf_checks.h) on the material whose answer is known, on the
// whole sphere and zoomed onto a 25° cap around a tilted axis (the rest is one cell).
TEST(LambertSharedChecks, SamplingFitsOnSphereAndOnZoomedCap) {
    const Lambert m(Rgb(0.5f, 0.6f, 0.7f));
    const Vec3 wo = directionFromDegrees(50, 30);
    const BsdfSamplingRun sphere = sampleBsdf(m, kCtx, wo, 300);
    EXPECT_EQ(sphere.weightMismatches, 0) << sphere.firstMismatch;
    EXPECT_EQ(sphere.nonFinite, 0);
    kChi2.expectFits(sphere.outcome, "Lambert, shared checks, whole sphere");
    BsdfHistogramLayout cap;
    cap.axis = directionFromDegrees(40, 100);
    cap.capDegrees = 25;
    cap.zCells = 20;
    cap.phiCells = 24;
    kChi2.expectFits(sampleBsdf(m, kCtx, wo, 301, 1000000, cap).outcome,
                     "Lambert, shared checks, 25° cap");
    const Rgb albedo = directionalAlbedo(m, kCtx, wo, 302);
    EXPECT_NEAR(albedo.g, 0.6f, 1e-5f);
    EXPECT_LT(reciprocityError(m, kCtx, 303), 1e-5);
}

TEST(Lambert, SampleWeightIsEvalOverPdf) {
    const Rgb albedo(0.5f, 0.6f, 0.7f);
    const Lambert m(albedo);
    for (const Vec3& wo : kWos)
        for (int i = 0; i < 20000; ++i) {
            BsdfSample s;
            if (!m.sample(kCtx, wo, uniform(3, i, 2), uniform2(3, i), &s)) {
                const Vec2 d = squareToUniformDisk(uniform2(3, i));
                ASSERT_GE(double(d.x) * d.x + double(d.y) * d.y, 1 - 1e-6)
                    << "declined above the horizon";
                continue;
            }
            EXPECT_GT(s.wi.z * wo.z, 0.0f) << "wi on the other side, wo = " << describe(wo);
            EXPECT_NEAR(length(s.wi), 1.0f, 1e-5f);
            EXPECT_FALSE(s.isSpecular());
            EXPECT_EQ(s.lobe, kReflection | kDiffuse);
            const float pdf = m.pdf(kCtx, wo, s.wi);
            EXPECT_NEAR(s.pdf, pdf, 1e-6f * pdf);
            const Rgb f = m.eval(kCtx, wo, s.wi);
            for (int c = 0; c < 3; ++c) {
                const float expected = f[c] / pdf;
                EXPECT_NEAR(s.weight[c], expected, 1e-4f * expected) << "wo = " << describe(wo);
            }
        }
}

TEST(Lambert, EvalAndPdfVanishOnTheOtherSide) {
    const Lambert m(Rgb(0.8f));
    for (int i = 0; i < 10000; ++i) {
        const Vec3 wo = normalize(
            Vec3(uniform(4, i, 0) * 2 - 1, uniform(4, i, 1) * 2 - 1, uniform(4, i, 2) * 2 - 1));
        const Vec3 wi = normalize(
            Vec3(uniform(4, i, 3) * 2 - 1, uniform(4, i, 4) * 2 - 1, uniform(4, i, 5) * 2 - 1));
        if (wo.z * wi.z < 0) {
            EXPECT_TRUE(m.eval(kCtx, wo, wi).isBlack()) << describe(wo) << " " << describe(wi);
            EXPECT_EQ(m.pdf(kCtx, wo, wi), 0.0f);
        } else if (wo.z * wi.z > 0) {
            EXPECT_NEAR(m.eval(kCtx, wo, wi).r, 0.8f / kPi * std::abs(wi.z), 1e-6f);
            EXPECT_NEAR(m.pdf(kCtx, wo, wi), std::abs(wi.z) / kPi, 1e-6f);
        }
    }
    // A grazing wo (z = 0) has no side: sample() declines.
    BsdfSample s;
    EXPECT_FALSE(m.sample(kCtx, Vec3(1, 0, 0), 0.5f, Vec2(0.3f, 0.6f), &s));
}

// f(wo, wi) = f(wi, wo), where eval = f·|cos θi|.
TEST(Lambert, EvalIsReciprocal) {
    const Lambert m(Rgb(0.3f, 0.6f, 0.9f));
    for (int i = 0; i < 10000; ++i) {
        const Vec3 wo = normalize(
            Vec3(uniform(5, i, 0) * 2 - 1, uniform(5, i, 1) * 2 - 1, uniform(5, i, 2) * 2 - 1));
        const Vec3 wi = normalize(
            Vec3(uniform(5, i, 3) * 2 - 1, uniform(5, i, 4) * 2 - 1, uniform(5, i, 5) * 2 - 1));
        if (wo.z == 0 || wi.z == 0) continue;
        const Rgb a = m.eval(kCtx, wo, wi), b = m.eval(kCtx, wi, wo);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(a[c] / std::abs(wi.z), b[c] / std::abs(wo.z), 1e-5f);
    }
}

// ∫ eval dωi over the hemisphere of wo is the albedo, and pdf integrates to one.
TEST(Lambert, EvalIntegratesToAlbedo) {
    const Lambert m(Rgb(0.3f, 0.6f, 0.9f));
    for (const Vec3& wo : kWos) {
        double e[3] = {0, 0, 0}, p = 0;
        const int nz = 2000, nphi = 64;
        for (int i = 0; i < nz; ++i)
            for (int j = 0; j < nphi; ++j) {
                const double z = -1 + (i + 0.5) * 2.0 / nz, phi = (j + 0.5) * 2 * M_PI / nphi;
                const double r = std::sqrt(1 - z * z);
                const Vec3 wi(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                const Rgb f = m.eval(kCtx, wo, wi);
                for (int c = 0; c < 3; ++c)
                    e[c] += f[c];
                p += m.pdf(kCtx, wo, wi);
            }
        const double dA = (2.0 / nz) * (2 * M_PI / nphi);
        EXPECT_NEAR(e[0] * dA, 0.3, 1e-4) << describe(wo);
        EXPECT_NEAR(e[1] * dA, 0.6, 1e-4) << describe(wo);
        EXPECT_NEAR(e[2] * dA, 0.9, 1e-4) << describe(wo);
        EXPECT_NEAR(p * dA, 1.0, 1e-4) << describe(wo);
    }
}

TEST(Lambert, PeakIsTheNormalOnTheSideOfWo) {
    const Lambert m(Rgb(0.5f));
    for (const Vec3& wo : kWos) {
        LobePeaks peaks;
        m.peaks(kCtx, wo, &peaks);
        ASSERT_EQ(peaks.count, 1);
        EXPECT_EQ(peaks.directions[0], Vec3(0, 0, wo.z > 0 ? 1.0f : -1.0f)) << describe(wo);
    }
    EXPECT_EQ(m.lobes(), kReflection | kDiffuse);
    EXPECT_TRUE(m.hasNonSpecular());
    EXPECT_FALSE(m.hasTransmission());
}

// --- Mirror -------------------------------------------------------------------------------------

TEST(Mirror, ReflectsAboutTheNormalWithReflectanceWeight) {
    const Rgb r(0.9f, 0.8f, 0.7f);
    const Mirror m(r);
    for (const Vec3& wo : kWos) {
        BsdfSample s;
        ASSERT_TRUE(m.sample(kCtx, wo, 0.3f, Vec2(0.1f, 0.9f), &s));
        EXPECT_EQ(s.wi, Vec3(-wo.x, -wo.y, wo.z)) << describe(wo);
        EXPECT_NEAR(length(reflect(wo, Vec3(0, 0, wo.z > 0 ? 1.0f : -1.0f)) - s.wi), 0.0f, 1e-6f);
        EXPECT_EQ(s.weight, r);
        EXPECT_EQ(s.pdf, 1.0f);
        EXPECT_TRUE(s.isSpecular());
        EXPECT_EQ(s.lobe, kReflection | kSpecular);
        EXPECT_TRUE(m.eval(kCtx, wo, s.wi).isBlack());
        EXPECT_EQ(m.pdf(kCtx, wo, s.wi), 0.0f);
        LobePeaks peaks;
        m.peaks(kCtx, wo, &peaks);
        ASSERT_EQ(peaks.count, 1);
        EXPECT_EQ(peaks.directions[0], s.wi);
    }
    EXPECT_FALSE(m.hasNonSpecular());
    EXPECT_FALSE(m.hasTransmission());
}

// --- Dielectric ---------------------------------------------------------------------------------

// Fresnel reflectance from the angles (Fresnel's sine and tangent laws), in double precision:
// an independent form of the same physics. η = ηt/ηi.
double fresnelFromAngles(double cosI, double eta) {
    if (cosI < 0) {
        eta = 1 / eta;
        cosI = -cosI;
    }
    const double thetaI = std::acos(std::min(1.0, cosI));
    const double sinT = std::sin(thetaI) / eta;
    if (sinT >= 1) return 1;
    const double thetaT = std::asin(sinT);
    if (thetaI < 1e-6) return std::pow((eta - 1) / (eta + 1), 2);
    const double rs = -std::sin(thetaI - thetaT) / std::sin(thetaI + thetaT);
    const double rp = std::tan(thetaI - thetaT) / std::tan(thetaI + thetaT);
    return 0.5 * (rs * rs + rp * rp);
}

TEST(Fresnel, NormalIncidenceIsSquaredRatio) {
    for (float eta : {1.0f, 1.33f, 1.5f, 2.4f}) {
        const float f0 = ((eta - 1) / (eta + 1)) * ((eta - 1) / (eta + 1));
        EXPECT_NEAR(fresnelDielectric(1.0f, eta), f0, 1e-6f) << "eta " << eta;
        EXPECT_NEAR(fresnelDielectric(-1.0f, eta), f0, 1e-6f) << "eta " << eta << " inside";
    }
}

TEST(Fresnel, MatchesFresnelsSineAndTangentLaws) {
    for (float eta : {1.33f, 1.5f, 2.4f})
        for (int k = 0; k <= 400; ++k) {
            const double cosI = -1 + 2.0 * k / 400;
            if (std::abs(cosI) < 1e-3) continue;
            const double expected = fresnelFromAngles(cosI, eta);
            EXPECT_NEAR(fresnelDielectric(float(cosI), eta), expected, 2e-5 + 1e-4 * expected)
                << "eta " << eta << ", cos " << cosI;
        }
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
    for (float eta : {1.33f, 1.5f, 2.4f}) {
        const double critical = std::asin(1.0 / eta);
        for (double theta = critical + 1e-3; theta < M_PI / 2; theta += 0.01)
            EXPECT_EQ(fresnelDielectric(-float(std::cos(theta)), eta), 1.0f)
                << "eta " << eta << ", theta " << theta;
        EXPECT_LT(fresnelDielectric(-float(std::cos(critical - 1e-3)), eta), 1.0f);
        // Entering from outside there is no critical angle.
        EXPECT_LT(fresnelDielectric(float(std::cos(M_PI / 2 - 1e-3)), eta), 1.0f);
    }
}

// F(θi) entering equals F(θt) leaving: the same interface seen from both sides.
TEST(Fresnel, IsTheSameFromBothSidesOfTheInterface) {
    for (float eta : {1.33f, 1.5f, 2.4f})
        for (double theta = 0; theta < 89.5; theta += 2.5) {
            const double thetaI = theta * M_PI / 180;
            const double thetaT = std::asin(std::sin(thetaI) / eta);
            const float outside = fresnelDielectric(float(std::cos(thetaI)), eta);
            const float inside = fresnelDielectric(-float(std::cos(thetaT)), eta);
            EXPECT_NEAR(outside, inside, 1e-5f + 1e-4f * outside)
                << "eta " << eta << ", theta " << theta;
        }
}

// Incident angles (from the normal on wo's side) with the side: outside, or inside below the
// critical angle of 41.8° for η = 1.5.
struct Incidence {
    double thetaDegrees;
    bool inside;
    Vec3 wo() const {
        const Vec3 w = directionFromDegrees(thetaDegrees, 35);
        return inside ? Vec3(w.x, w.y, -w.z) : w;
    }
};
const Incidence kIncidences[] = {{0, false}, {45, false}, {80, false}, {20, true}, {40, true}};

TEST(Dielectric, RefractionObeysSnellsLaw) {
    const float eta = 1.5f;
    const Dielectric m(eta, Rgb(1.0f), Rgb(1.0f));
    for (const Incidence& inc : kIncidences) {
        const Vec3 wo = inc.wo();
        BsdfSample s;
        ASSERT_TRUE(m.sample(kCtx, wo, 1.0f - 0x1p-24f, Vec2(0.5f, 0.5f), &s));
        ASSERT_EQ(s.lobe, kTransmission | kSpecular) << inc.thetaDegrees;
        EXPECT_LT(s.wi.z * wo.z, 0.0f) << "refracted to the same side";
        EXPECT_NEAR(length(s.wi), 1.0f, 1e-6f);
        const double sinI = std::sqrt(double(wo.x) * wo.x + double(wo.y) * wo.y);
        const double sinT = std::sqrt(double(s.wi.x) * s.wi.x + double(s.wi.y) * s.wi.y);
        const double etaI = inc.inside ? eta : 1.0, etaT = inc.inside ? 1.0 : eta;
        EXPECT_NEAR(etaI * sinI, etaT * sinT, 1e-6) << "theta " << inc.thetaDegrees;
        // In the plane of incidence, on the far side of the normal.
        EXPECT_NEAR(double(wo.x) * s.wi.y - double(wo.y) * s.wi.x, 0.0, 1e-6);
        EXPECT_LE(double(wo.x) * s.wi.x + double(wo.y) * s.wi.y, 0.0);
    }
}

TEST(Dielectric, WeightsAndProbabilitiesOfBothLobes) {
    const float eta = 1.5f;
    const Rgb reflectance(0.9f, 0.8f, 0.7f), transmittance(0.5f, 0.6f, 0.7f);
    const Dielectric m(eta, reflectance, transmittance);
    for (const Incidence& inc : kIncidences) {
        const Vec3 wo = inc.wo();
        const float f = fresnelDielectric(wo.z, eta);
        EXPECT_EQ(m.reflectProbability(wo), f);
        BsdfSample r, t;
        ASSERT_TRUE(m.sample(kCtx, wo, 0.0f, Vec2(0.2f, 0.7f), &r));
        EXPECT_EQ(r.lobe, kReflection | kSpecular);
        EXPECT_EQ(r.wi, Vec3(-wo.x, -wo.y, wo.z));
        EXPECT_FLOAT_EQ(r.pdf, f);
        EXPECT_EQ(r.weight, reflectance);  // F·R / F
        ASSERT_TRUE(m.sample(kCtx, wo, 1.0f - 0x1p-24f, Vec2(0.2f, 0.7f), &t));
        EXPECT_EQ(t.lobe, kTransmission | kSpecular);
        EXPECT_FLOAT_EQ(t.pdf, 1.0f - f);
        // (1 − F)·T/η² / (1 − F), η = ηt/ηi: 1.5 entering, 1/1.5 leaving.
        const float etaRel = inc.inside ? 1.0f / eta : eta;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(t.weight[c], transmittance[c] / (etaRel * etaRel),
                        1e-6f * transmittance[c] / (etaRel * etaRel))
                << "theta " << inc.thetaDegrees << (inc.inside ? " inside" : " outside");
        EXPECT_TRUE(m.eval(kCtx, wo, t.wi).isBlack());
        EXPECT_EQ(m.pdf(kCtx, wo, t.wi), 0.0f);
        // Peaks: the mirror direction and the refracted direction.
        LobePeaks peaks;
        m.peaks(kCtx, wo, &peaks);
        ASSERT_EQ(peaks.count, 2);
        EXPECT_EQ(peaks.directions[0], r.wi);
        EXPECT_EQ(peaks.directions[1], t.wi);
    }
    EXPECT_EQ(m.lobes(), kReflection | kTransmission | kSpecular);
    EXPECT_TRUE(m.hasTransmission());
    EXPECT_FALSE(m.hasNonSpecular());
}

TEST(Dielectric, TotalInternalReflectionAlwaysReflects) {
    const Dielectric m(1.5f, Rgb(0.9f), Rgb(0.5f));
    for (double theta : {42.0, 60.0, 89.0}) {
        const Vec3 w = directionFromDegrees(theta, 10);
        const Vec3 wo(w.x, w.y, -w.z);
        for (int k = 0; k < 1000; ++k) {
            BsdfSample s;
            ASSERT_TRUE(m.sample(kCtx, wo, (k + 0.5f) / 1000, Vec2(0.5f, 0.5f), &s));
            EXPECT_EQ(s.lobe, kReflection | kSpecular);
            EXPECT_EQ(s.pdf, 1.0f);
            EXPECT_EQ(s.wi, Vec3(-wo.x, -wo.y, wo.z));
        }
        LobePeaks peaks;
        m.peaks(kCtx, wo, &peaks);
        EXPECT_EQ(peaks.count, 1) << "no refracted peak under total internal reflection";
    }
}

// The reflect/transmit choice: sweeping uLobe over a regular grid reflects a fraction F (exact
// up to the grid step), and 10⁶ random uLobe reflect a binomial fraction F (z-test).
TEST(Dielectric, ReflectedFractionIsFresnel) {
    const float eta = 1.5f;
    const Dielectric m(eta, Rgb(1.0f), Rgb(1.0f));
    for (const Incidence& inc : kIncidences) {
        const Vec3 wo = inc.wo();
        const double f = fresnelFromAngles(wo.z, eta);
        const int grid = 100000;
        int reflected = 0;
        for (int k = 0; k < grid; ++k) {
            BsdfSample s;
            ASSERT_TRUE(m.sample(kCtx, wo, (k + 0.5f) / grid, Vec2(0.5f, 0.5f), &s));
            reflected += (s.lobe & kReflection) != 0;
        }
        EXPECT_NEAR(double(reflected) / grid, f, 2.0 / grid + 1e-5) << inc.thetaDegrees;

        reflected = 0;
        for (int i = 0; i < kSamples; ++i) {
            BsdfSample s;
            ASSERT_TRUE(m.sample(kCtx, wo, uniform(7, i, uint64_t(inc.thetaDegrees)),
                                 Vec2(0.5f, 0.5f), &s));
            reflected += (s.lobe & kReflection) != 0;
        }
        const double z = (reflected - kSamples * f) / std::sqrt(kSamples * f * (1 - f));
        std::printf("[z] reflected fraction at %g deg %s: %.6f vs F = %.6f, z = %.2f\n",
                    inc.thetaDegrees, inc.inside ? "inside" : "outside",
                    double(reflected) / kSamples, f, z);
        EXPECT_LT(std::abs(z), kZ) << "theta " << inc.thetaDegrees;
    }
}

// Negative control: the z-test tells the exact Fresnel term from Schlick's approximation at
// 70°, where they differ by about 0.017.
TEST(DielectricNegativeControl, ReflectedFractionIsNotSchlick) {
    const float eta = 1.5f;
    const Dielectric m(eta, Rgb(1.0f), Rgb(1.0f));
    const Vec3 wo = directionFromDegrees(70, 0);
    const double r0 = std::pow((eta - 1) / (eta + 1), 2);
    const double schlick = r0 + (1 - r0) * std::pow(1 - wo.z, 5);
    int reflected = 0;
    for (int i = 0; i < kSamples; ++i) {
        BsdfSample s;
        m.sample(kCtx, wo, uniform(8, i, 0), Vec2(0.5f, 0.5f), &s);
        reflected += (s.lobe & kReflection) != 0;
    }
    const double z =
        (reflected - kSamples * schlick) / std::sqrt(kSamples * schlick * (1 - schlick));
    std::printf("[z, negative control] reflected fraction vs Schlick: z = %.2f\n", z);
    EXPECT_GT(std::abs(z), kZ);
}

}  // namespace
}  // namespace rr::test
