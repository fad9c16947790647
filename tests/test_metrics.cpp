// The metrics library against hand-computed values on tiny images and point lists: MSE, RMSE,
// σ/µ, relMSE with and without rejection, the Ferwerda TVI branches, the tvi error, per-channel
// and luminance variants, efficiencies, log-log slopes, merging, and typed errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "math/tvi.h"
#include "metrics/image_metrics.h"
#include "metrics/merge.h"
#include "metrics/metrics_error.h"
#include "metrics/regression.h"

namespace rr::test {
namespace {

using Json = nlohmann::json;

// Relative tolerance for values written down to 7 significant digits.
void expectClose(double actual, double expected) {
    EXPECT_NEAR(actual, expected, 1e-6 * std::abs(expected) + 1e-12);
}

// An image from one RGB triple per pixel, row-major.
InputImage inputImage(int width, int height, const std::vector<std::array<double, 3>>& pixels,
                      const std::string& source = "image.exr") {
    InputImage image{source, width, height, {}};
    for (const auto& p : pixels)
        for (size_t c = 0; c < 3; ++c)
            image.channels[c].push_back(p[c]);
    return image;
}

// The 2×2 case every compare test uses. Reference (grey pixels, so Y = the value) and image:
//   pixel      reference   image        difference
//   (0,0)      1 1 1       2 1 1        1  0  0
//   (1,0)      3 3 3       3 3 1        0  0 −2
//   (0,1)      2 2 2       2 2 2        0  0  0
//   (1,1)      2 2 2       2 2 2.5      0  0  0.5
InputImage reference2x2() {
    return inputImage(2, 2, {{1, 1, 1}, {3, 3, 3}, {2, 2, 2}, {2, 2, 2}}, "reference.exr");
}
InputImage image2x2() {
    return inputImage(2, 2, {{2, 1, 1}, {3, 3, 1}, {2, 2, 2}, {2, 2, 2.5}});
}

// Expects `f` to throw MetricsError with `mentions` in its message.
template <class F>
void expectMetricsError(F f, const std::string& mentions) {
    try {
        f();
        ADD_FAILURE() << "no MetricsError; expected one mentioning " << mentions;
    } catch (const MetricsError& e) {
        EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
    }
}

TEST(Metrics, MseRmseSigmaOverMuAndRelmse) {
    const Comparison c = compareImages(image2x2(), reference2x2());
    // Squared differences 1, 4, 0.25 over 12 values: mse = 5.25/12 = 0.4375,
    // rmse = 0.6614378; reference mean (3 + 9 + 6 + 6)/12 = 2, σ/µ = 0.3307189.
    EXPECT_DOUBLE_EQ(c.rgb.mse, 0.4375);
    expectClose(c.rgb.rmse, 0.6614378);
    EXPECT_DOUBLE_EQ(c.rgb.referenceMean, 2.0);
    expectClose(*c.rgb.sigmaOverMu, 0.3307189);
    // Image mean (4 + 7 + 6 + 6.5)/12 = 23.5/12: relative bias 23.5/24 − 1 = −1/48.
    expectClose(c.rgb.mean, 23.5 / 12);
    expectClose(*c.rgb.relativeBias, -1.0 / 48);
    // relMSE: (1/1.01 + 4/9.01 + 0.25/4.01)/12 = (0.9900990 + 0.4439512 + 0.0623441)/12.
    expectClose(c.rgb.relmse, 0.1246995);
    EXPECT_EQ(c.width, 2);
    EXPECT_EQ(c.height, 2);
}

TEST(Metrics, RelmseRejectionDropsThePixelsWithTheLargestValues) {
    // Per-pixel relMSE (mean over the pixel's channels): (0,0) 0.9900990/3 = 0.3300330,
    // (1,0) 0.4439512/3 = 0.1479837, (0,1) 0, (1,1) 0.0623441/3 = 0.0207814. Rejecting
    // floor(0.25·4) = 1 pixel drops (0,0): (0.1479837 + 0 + 0.0207814)/3 = 0.0562550.
    const Comparison c = compareImages(image2x2(), reference2x2(), {0.25, kDefaultCdPerUnit});
    expectClose(c.rgb.relmse, 0.0562550);
    // floor(0.2·4) = 0 pixels: nothing is dropped.
    expectClose(compareImages(image2x2(), reference2x2(), {0.2, 100}).rgb.relmse, 0.1246995);
}

TEST(Metrics, PhotopicTviBranchesAtAndAroundTheirBreakpoints) {
    // Lower plateau, log10 La ≤ −2.6: 10^−0.72 = 0.1905461.
    expectClose(photopicTvi(1e-3), 0.1905461);
    expectClose(photopicTvi(std::pow(10.0, -2.6)), 0.1905461);
    expectClose(photopicTvi(0), 0.1905461);
    expectClose(photopicTvi(-5), 0.1905461);
    // Middle, log10 La = −2.5: (0.249·−2.5 + 0.65)^2.7 = 0.0275^2.7 = 6.112210e-5, minus 0.72
    // = −0.7199389, so 0.1905729.
    expectClose(photopicTvi(std::pow(10.0, -2.5)), 0.1905729);
    // Middle, La = 1: 0.65^2.7 = 0.3125115, −0.72 → −0.4074885, 10^ = 0.3913015.
    expectClose(photopicTvi(1), 0.3913015);
    // Middle, log10 La = 1.8: (0.249·1.8 + 0.65)^2.7 = 1.0982^2.7 = 1.2877747, −0.72 →
    // 0.5677747, 10^ = 3.696364.
    expectClose(photopicTvi(std::pow(10.0, 1.8)), 3.696364);
    // Upper, log10 La ≥ 1.9: log10 La − 1.255. At 10^1.9: 10^0.645 = 4.415704; at 100:
    // 10^0.745 = 5.559043.
    expectClose(photopicTvi(std::pow(10.0, 1.9)), 4.415704);
    expectClose(photopicTvi(100), 5.559043);
}

TEST(Metrics, PhotopicTviPiecesNearlyMeetAtTheBreakpoints) {
    // The published fits leave gaps in log10 tvi. Just above −2.6 the middle piece gives
    // 0.0026^2.7 − 0.72, 1.048e-7 above the plateau; just below 1.9 it gives
    // 1.1231^2.7 − 0.72 = 0.6481375 against the upper piece's 0.645.
    EXPECT_NEAR(std::log10(photopicTvi(std::pow(10.0, -2.6 + 1e-9))) + 0.72, 1.048e-7, 1e-9);
    EXPECT_NEAR(std::log10(photopicTvi(std::pow(10.0, 1.9 - 1e-9))), 0.6481375, 1e-6);
    EXPECT_NEAR(std::log10(photopicTvi(std::pow(10.0, 1.9))), 0.645, 1e-12);
}

TEST(Metrics, ScotopicTviBranchesAtAndAroundTheirBreakpoints) {
    // Lower plateau, log10 La ≤ −3.94: 10^−2.86 = 0.001380384.
    expectClose(scotopicTvi(1e-4), 0.001380384);
    expectClose(scotopicTvi(std::pow(10.0, -3.94)), 0.001380384);
    expectClose(scotopicTvi(0), 0.001380384);
    // Middle, log10 La = −3: (0.405·−3 + 1.6)^2.2 = 0.385^2.2 = 0.1224655, −2.86 → −2.7375345,
    // 10^ = 0.001830061.
    expectClose(scotopicTvi(1e-3), 0.001830061);
    // Middle, log10 La = −1.5: 0.9925^2.2 = 0.9835742, −2.86 → −1.8764258, 10^ = 0.01329151.
    expectClose(scotopicTvi(std::pow(10.0, -1.5)), 0.01329151);
    // Upper, log10 La ≥ −1.44: log10 La − 0.395. At 10^−1.44: 10^−1.835 = 0.01462177; at 1:
    // 10^−0.395 = 0.4027170.
    expectClose(scotopicTvi(std::pow(10.0, -1.44)), 0.01462177);
    expectClose(scotopicTvi(1), 0.4027170);
    // The gap at −1.44: just below it the middle piece gives 1.0168^2.2 − 2.86 = −1.8226670,
    // 0.0123330 above the upper piece's −1.835.
    EXPECT_NEAR(std::log10(scotopicTvi(std::pow(10.0, -1.44 - 1e-9))), -1.8226670, 1e-6);
}

TEST(Metrics, TviErrorOnLuminanceDifferences) {
    // Reference Y (cd/m², scale 100): 100, 300, 200, 200, all ≥ 10^1.9, where
    // tvi(L) = L·10^−1.255. Image Y − reference Y per pixel: 0.2126·1 = 0.2126,
    // 0.0722·−2 = −0.1444, 0, 0.0722·0.5 = 0.0361. So
    // tvi_err = (1/4) Σ (100 d)² / (100 Y·10^−1.255) = 25·10^1.255·Σ d²/Y
    //         = 25·17.98871·(0.04519876/1 + 0.02085136/3 + 0.00130321/2) = 23.74546.
    const Comparison c = compareImages(image2x2(), reference2x2());
    expectClose(c.rgb.tviErr, 23.74546);
    EXPECT_EQ(c.luminance.tviErr, c.rgb.tviErr);
    // A scale of 1 puts La = Y in the middle piece: one pixel, reference (1,1,1), image
    // (2,1,1): e = 0.2126, tvi(1) = 0.3913015, tvi_err = 0.04519876/0.3913015 = 0.1155088.
    const Comparison one = compareImages(inputImage(1, 1, {{2, 1, 1}}),
                                         inputImage(1, 1, {{1, 1, 1}}, "reference.exr"), {0, 1});
    expectClose(one.rgb.tviErr, 0.1155088);
}

TEST(Metrics, PerChannelAndLuminanceVariants) {
    const Comparison c = compareImages(image2x2(), reference2x2());
    // R: differences (1, 0, 0, 0); mean R of the reference (1 + 3 + 2 + 2)/4 = 2.
    // mse 0.25, rmse 0.5, σ/µ 0.25, relMSE (1/1.01)/4 = 0.2475248,
    // tvi_err (100·1)²/(100·10^−1.255)/4 = 25·10^1.255 = 449.7177.
    const ErrorStats& r = c.channels[0];
    EXPECT_DOUBLE_EQ(r.mse, 0.25);
    EXPECT_DOUBLE_EQ(r.rmse, 0.5);
    EXPECT_DOUBLE_EQ(*r.sigmaOverMu, 0.25);
    expectClose(r.relmse, 0.2475248);
    expectClose(r.tviErr, 449.7177);
    // G: no difference at all.
    EXPECT_EQ(c.channels[1].mse, 0);
    EXPECT_EQ(c.channels[1].relmse, 0);
    EXPECT_EQ(c.channels[1].tviErr, 0);
    EXPECT_EQ(*c.channels[1].sigmaOverMu, 0);
    // B: differences (0, −2, 0, 0.5): mse 4.25/4 = 1.0625, rmse 1.0307764, σ/µ 0.5153882,
    // relMSE (4/9.01 + 0.25/4.01)/4 = 0.1265738,
    // tvi_err (200²/300 + 50²/200)·10^1.255/4 = 145.83333·17.98871/4 = 655.8384.
    const ErrorStats& b = c.channels[2];
    EXPECT_DOUBLE_EQ(b.mse, 1.0625);
    expectClose(b.rmse, 1.0307764);
    expectClose(*b.sigmaOverMu, 0.5153882);
    expectClose(b.relmse, 0.1265738);
    expectClose(b.tviErr, 655.8384);
    // Luminance: differences (0.2126, −0.1444, 0, 0.0361): mse
    // (0.04519876 + 0.02085136 + 0.00130321)/4 = 0.01683833, rmse 0.1297626, reference mean
    // Y 2, σ/µ 0.0648813, relMSE (0.04519876/1.01 + 0.02085136/9.01 + 0.00130321/4.01)/4
    // = 0.01184762.
    const ErrorStats& y = c.luminance;
    expectClose(y.mse, 0.01683833);
    expectClose(y.rmse, 0.1297626);
    EXPECT_DOUBLE_EQ(y.referenceMean, 2.0);
    expectClose(*y.sigmaOverMu, 0.0648813);
    expectClose(y.relmse, 0.01184762);
}

TEST(Metrics, ChannelSigmaOverMuIsAbsentForAZeroChannelMean) {
    // Reference (1, 0, 1): the G mean is 0, the RGB mean 2/3.
    const Comparison c = compareImages(inputImage(1, 1, {{1, 1, 1}}),
                                       inputImage(1, 1, {{1, 0, 1}}, "reference.exr"));
    EXPECT_FALSE(c.channels[1].sigmaOverMu.has_value());
    expectClose(*c.rgb.sigmaOverMu, std::sqrt(1.0 / 3) / (2.0 / 3));
}

TEST(Metrics, Efficiencies) {
    // P-Eff = 1/(T·tvi_err) = 1/(2·23.74546) = 0.02105665; 1/(T·mse) = 1/(2·0.4375) = 8/7.
    const Comparison c = compareImages(image2x2(), reference2x2());
    expectClose(*efficiency(c.rgb.tviErr, 2), 0.02105665);
    EXPECT_DOUBLE_EQ(*efficiency(c.rgb.mse, 2), 8.0 / 7.0);
    EXPECT_FALSE(efficiency(0, 2).has_value());
    EXPECT_FALSE(efficiency(std::numeric_limits<double>::denorm_min(), 1e-10).has_value());
}

TEST(Metrics, SlopeOfAnExactPowerLaw) {
    // error = spp^−0.5: log error = −0.5 log spp exactly.
    std::vector<ConvergencePoint> points;
    for (double spp : {1, 4, 16, 64})
        points.push_back({spp, 1 / std::sqrt(spp), spp * 0.25});
    const ConvergenceSlopes s = convergenceSlopes(points);
    EXPECT_NEAR(s.vsSpp.slope, -0.5, 1e-12);
    EXPECT_NEAR(s.vsSpp.intercept, 0, 1e-12);
    EXPECT_NEAR(s.vsSpp.slopeStderr, 0, 1e-12);
    EXPECT_NEAR(s.vsSpp.r2, 1, 1e-12);
    EXPECT_EQ(s.vsSpp.n, 4u);
    ASSERT_TRUE(s.vsTime.has_value());
    EXPECT_NEAR(s.vsTime->slope, -0.5, 1e-12);
}

TEST(Metrics, SlopeOfNoisyPoints) {
    // spp 1, 2, 4, 8 (x = u·ln 2, u = 0..3), log error y = 0, −0.5, −0.6, −1.2.
    // In u: ū = 1.5, ȳ = −0.575, Suu = 5, Suy = −1.5·0.575 − 0.5·0.075 − 0.5·0.025 − 1.5·0.625
    // = −1.85, slope −0.37 per doubling, intercept −0.575 + 0.37·1.5 = −0.02. Residuals
    // 0.02, −0.11, 0.16, −0.07: RSS 0.043; TSS 0.7275; R² = 1 − 0.043/0.7275 = 0.9408935.
    // Stderr in u: sqrt(0.043/2/5) = 0.06557439. In x divide slope and stderr by
    // ln 2 = 0.6931472: slope −0.5337972, stderr 0.09460384.
    // With time = spp/2, log time = x − ln 2, so the intercept becomes −0.02 − 0.37 = −0.39.
    const double y[] = {0, -0.5, -0.6, -1.2};
    std::vector<ConvergencePoint> points;
    for (int u = 0; u < 4; ++u)
        points.push_back({std::ldexp(1.0, u), std::exp(y[u]), std::ldexp(0.5, u)});
    const ConvergenceSlopes s = convergenceSlopes(points);
    expectClose(s.vsSpp.slope, -0.5337972);
    expectClose(s.vsSpp.slopeStderr, 0.09460384);
    expectClose(s.vsSpp.intercept, -0.02);
    expectClose(s.vsSpp.r2, 0.9408935);
    expectClose(s.vsTime->slope, -0.5337972);
    expectClose(s.vsTime->intercept, -0.39);
}

TEST(Metrics, SlopePointsParseBothFormsAndTimeIsOptional) {
    const Json list = Json::parse(R"([{"spp": 1, "error": 1, "time": 2},
                                      {"spp": 4, "error": 0.5, "label": "ignored"},
                                      {"spp": 16, "error": 0.25, "time": 8}])");
    const std::vector<ConvergencePoint> points = parseConvergencePoints(list);
    ASSERT_EQ(points.size(), 3u);
    EXPECT_EQ(points[1].spp, 4);
    EXPECT_FALSE(points[1].time.has_value());
    EXPECT_EQ(*points[2].time, 8);
    EXPECT_FALSE(convergenceSlopes(points).vsTime.has_value());
    EXPECT_EQ(parseConvergencePoints(Json{{"points", list}}).size(), 3u);
}

TEST(Metrics, SlopeRejectsBadPointsByPointerAndTooFewPoints) {
    const Json good = {{"spp", 1}, {"error", 1}};
    expectMetricsError(
        [&] {
            parseConvergencePoints(Json{{"points", {good, {{"spp", 2}, {"error", 0}}}}});
        },
        "/points/1/error");
    expectMetricsError(
        [&] {
            parseConvergencePoints(Json{good, {{"spp", -1}, {"error", 1}}});
        },
        "/1/spp");
    expectMetricsError([&] { parseConvergencePoints(Json{good, {{"spp", 2}}}); }, "\"error\"");
    expectMetricsError(
        [&] {
            parseConvergencePoints(Json{good, {{"spp", 2}, {"error", 1}, {"time", "x"}}});
        },
        "/1/time");
    expectMetricsError([&] { parseConvergencePoints(Json{{"points", 3}}); }, "/points");
    expectMetricsError([&] { convergenceSlopes({{1, 1, {}}, {2, 0.5, {}}}); }, "too few points");
    expectMetricsError(
        [&] {
            convergenceSlopes({{4, 1, {}}, {4, 0.5, {}}, {4, 0.7, {}}});
        },
        "same spp");
}

ExrImage exrImage(int width, int height, const std::vector<float>& r, const std::vector<float>& g,
                  const std::vector<float>& b) {
    ExrImage image;
    image.width = width;
    image.height = height;
    image.channels = {{"R", r}, {"G", g}, {"B", b}};
    return image;
}

TEST(Metrics, MergeWeightsBySppAndCombinesVariances) {
    // 2×1 images; A has 1 spp, B 3 spp: weights 1/4 and 3/4.
    // A = (4,4,4), (0,0,0); B = (0,0,0), (4,8,4) → merged (1,1,1), (3,6,3), mean 15/6 = 2.5.
    // Variances 16 (A) and 16/9 (B): Σ w² v = 16/16 + (9/16)(16/9) = 2.
    ExrImage a = exrImage(2, 1, {4, 0}, {4, 0}, {4, 0});
    ExrImage b = exrImage(2, 1, {0, 4}, {0, 8}, {0, 4});
    for (const char* v : {"variance.R", "variance.G", "variance.B"}) {
        a.channels[v] = {16, 16};
        b.channels[v] = {16.0f / 9, 16.0f / 9};
    }
    a.attributes = {{"renderer.spp", 1},
                    {"renderer.renderTime", 1.0},
                    {"renderer.integrator", std::string("path")}};
    b.attributes = {{"renderer.spp", 3}, {"renderer.renderTime", 2.0}};
    const MergedReference m = mergeImages({a, b}, {"a.exr", "b.exr"});
    EXPECT_EQ(m.image.channels.at("R"), (std::vector<float>{1, 3}));
    EXPECT_EQ(m.image.channels.at("G"), (std::vector<float>{1, 6}));
    EXPECT_EQ(m.image.channels.at("B"), (std::vector<float>{1, 3}));
    for (const char* v : {"variance.R", "variance.G", "variance.B"}) {
        expectClose(m.image.channels.at(v)[0], 2);
        expectClose(m.image.channels.at(v)[1], 2);
    }
    EXPECT_DOUBLE_EQ(m.mean, 2.5);
    EXPECT_EQ(*m.spp, 4);
    EXPECT_FALSE(m.noise.has_value()) << "unequal spp: no half-difference estimate";
    const auto& attributes = m.image.attributes;
    EXPECT_EQ(std::get<std::string>(attributes.at("reference.sources")), "a.exr,b.exr");
    EXPECT_EQ(std::get<int>(attributes.at("reference.spp")), 4);
    EXPECT_EQ(std::get<double>(attributes.at("reference.renderTime")), 3.0);
    EXPECT_EQ(std::get<std::string>(attributes.at("renderer.integrator")), "path");
    EXPECT_FALSE(attributes.count("reference.noiseRmse"));
}

TEST(Metrics, MergeOfTwoEqualHalvesEstimatesItsNoise) {
    // A = (1,2,3), (5,5,5); B = (3,2,1), (5,5,9), no spp (equal weights), no variances.
    // A − B = (−2,0,2), (0,0,−4): RMS sqrt((4 + 4 + 16)/6) = 2, noise rmse 1.
    // Merged (2,2,2), (5,5,7): mean 23/6, noise σ/µ = 6/23.
    const ExrImage a = exrImage(2, 1, {1, 5}, {2, 5}, {3, 5});
    ExrImage b = exrImage(2, 1, {3, 5}, {2, 5}, {1, 9});
    b.channels["variance.R"] = {1, 1};  // only one input has variances: none are written
    const MergedReference m = mergeImages({a, b}, {"a.exr", "b.exr"});
    EXPECT_EQ(m.image.channels.at("B"), (std::vector<float>{2, 7}));
    EXPECT_FALSE(m.image.channels.count("variance.R"));
    EXPECT_FALSE(m.spp.has_value());
    ASSERT_TRUE(m.noise.has_value());
    EXPECT_DOUBLE_EQ(m.noise->halfDifferenceRmse, 2);
    EXPECT_DOUBLE_EQ(m.noise->noiseRmse, 1);
    EXPECT_DOUBLE_EQ(*m.noise->noiseSigmaOverMu, 6.0 / 23);
    EXPECT_DOUBLE_EQ(std::get<double>(m.image.attributes.at("reference.noiseRmse")), 1);
    EXPECT_DOUBLE_EQ(std::get<double>(m.image.attributes.at("reference.noiseSigmaOverMu")),
                     6.0 / 23);
    EXPECT_FALSE(m.image.attributes.count("reference.spp"));
}

TEST(Metrics, BadImagesThrowTypedErrorsNamingTheProblem) {
    const InputImage small = inputImage(1, 1, {{1, 1, 1}}, "small.exr");
    expectMetricsError([&] { compareImages(small, reference2x2()); },
                       "small.exr is 1x1 but the reference reference.exr is 2x2");
    expectMetricsError(
        [&] {
            compareImages(small, inputImage(1, 1, {{0, 0, 0}}, "zero.exr"));
        },
        "zero.exr has mean 0");
    expectMetricsError(
        [&] {
            compareImages(small, inputImage(1, 1, {{1, -2, 0}}, "neg.exr"));
        },
        "neg.exr has mean -0.333333");
    expectMetricsError(
        [&] {
            compareImages(image2x2(), reference2x2(), {0.5, 100});
        },
        "--relmse-reject");
    expectMetricsError([&] { compareImages(image2x2(), reference2x2(), {0, 0}); }, "--cd-per-unit");

    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    expectMetricsError(
        [&] {
            inputFromExr(exrImage(2, 2, {0, 0, 0, 0}, {0, 0, 0, nan}, {0, 0, 0, 0}), "nan.exr");
        },
        "nan.exr: NaN value in channel G at pixel (1, 1)");
    expectMetricsError(
        [&] {
            inputFromExr(exrImage(2, 1, {0, 0}, {0, 0}, {-inf, 0}), "inf.exr");
        },
        "inf.exr: infinite value in channel B at pixel (0, 0)");
    ExrImage noBlue = exrImage(1, 1, {0}, {0}, {0});
    noBlue.channels.erase("B");
    expectMetricsError([&] { inputFromExr(noBlue, "rg.exr"); }, "rg.exr: no channel B");
}

TEST(Metrics, BadMergeInputsThrowTypedErrors) {
    const ExrImage a = exrImage(2, 1, {1, 1}, {1, 1}, {1, 1});
    expectMetricsError([&] { mergeImages({a}, {"a.exr"}); }, "at least 2");
    expectMetricsError(
        [&] {
            mergeImages({a, exrImage(1, 1, {1}, {1}, {1})}, {"a.exr", "b.exr"});
        },
        "b.exr is 1x1 but a.exr is 2x1");
    ExrImage badVariance = a, zeroSpp = a;
    for (const char* v : {"variance.R", "variance.G", "variance.B"}) {
        badVariance.channels[v] = {0, 0};
        zeroSpp.channels[v] = {0, 0};
    }
    badVariance.channels["variance.G"][1] = std::numeric_limits<float>::quiet_NaN();
    expectMetricsError(
        [&] {
            mergeImages({zeroSpp, badVariance}, {"a.exr", "b.exr"});
        },
        "b.exr: NaN value in channel variance.G at pixel (1, 0)");
    zeroSpp.attributes["renderer.spp"] = 0;
    expectMetricsError(
        [&] {
            mergeImages({a, zeroSpp}, {"a.exr", "z.exr"});
        },
        "z.exr: renderer.spp is 0");
}

}  // namespace
}  // namespace rr::test
