// The metrics binary end to end: compare, slope and merge outputs, the render time taken from
// the image's metadata, and exit status 2 with one stderr line and nothing written for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "io/exr_io.h"
#include "support/child_process.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

using Result = ProcessResult;

Result run(const std::vector<std::string>& args, const fs::path& dir) {
    return runProcess(METRICS_BINARY, args, dir);
}

// Writes an image from one RGB triple per pixel, row-major.
void writeRgb(const fs::path& file, int width, int height,
              const std::vector<std::array<float, 3>>& pixels,
              const std::map<std::string, ExrAttributeValue>& attributes = {}) {
    ExrImage image;
    image.width = width;
    image.height = height;
    for (const auto& p : pixels)
        for (size_t c = 0; c < 3; ++c)
            image.channels[std::string(1, "RGB"[c])].push_back(p[c]);
    image.attributes = attributes;
    writeExr(file, image);
}

// The 2×2 case of test_metrics.cpp, whose values are computed by hand there.
void writeCase(const fs::path& dir, const std::map<std::string, ExrAttributeValue>& attributes) {
    writeRgb(dir / "image.exr", 2, 2, {{2, 1, 1}, {3, 3, 1}, {2, 2, 2}, {2, 2, 2.5}}, attributes);
    writeRgb(dir / "reference.exr", 2, 2, {{1, 1, 1}, {3, 3, 3}, {2, 2, 2}, {2, 2, 2}});
}

TEST(MetricsCli, CompareJsonHasEveryMetric) {
    const fs::path dir = scratchDirectory();
    writeCase(dir, {{"renderer.spp", 16}});
    const Result r = run({"compare", (dir / "image.exr").string(), (dir / "reference.exr").string(),
                          "--json", "--time", "2"},
                         dir);
    ASSERT_EQ(r.status, 0) << r.errors;
    EXPECT_EQ(r.errors, "");
    const Json j = Json::parse(r.out);
    EXPECT_DOUBLE_EQ(j["mse"].get<double>(), 0.4375);
    EXPECT_NEAR(j["rmse"].get<double>(), 0.6614378, 1e-6);
    EXPECT_NEAR(j["sigma_over_mu"].get<double>(), 0.3307189, 1e-6);
    EXPECT_DOUBLE_EQ(j["reference_mean"].get<double>(), 2);
    EXPECT_NEAR(j["relative_bias"].get<double>(), -1.0 / 48, 1e-12);
    EXPECT_NEAR(j["relmse"].get<double>(), 0.1246995, 1e-6);
    EXPECT_EQ(j["relmse_reject_fraction"].get<double>(), 0);
    EXPECT_NEAR(j["tvi_err"].get<double>(), 23.74546, 1e-4);
    EXPECT_EQ(j["cd_per_unit"].get<double>(), 100);
    EXPECT_EQ(j["width"], 2);
    EXPECT_EQ(j["height"], 2);
    EXPECT_EQ(j["spp"], 16);
    EXPECT_EQ(j["image"], (dir / "image.exr").string());
    EXPECT_EQ(j["time"].get<double>(), 2);
    EXPECT_NEAR(j["p_eff"].get<double>(), 1 / (2 * j["tvi_err"].get<double>()), 1e-15);
    EXPECT_DOUBLE_EQ(j["mse_eff"].get<double>(), 8.0 / 7.0);
    EXPECT_DOUBLE_EQ(j["channels"]["R"]["sigma_over_mu"].get<double>(), 0.25);
    EXPECT_NEAR(j["channels"]["B"]["tvi_err"].get<double>(), 655.8384, 1e-3);
    EXPECT_NEAR(j["luminance"]["relmse"].get<double>(), 0.01184762, 1e-8);
    for (const char* key : {"rmse", "mse", "sigma_over_mu", "relmse"})
        EXPECT_TRUE(j["luminance"].contains(key)) << key;
}

TEST(MetricsCli, CompareTakesTheTimeFromTheImageMetadata) {
    const fs::path dir = scratchDirectory();
    writeCase(dir, {{"renderer.renderTime", 0.5}});
    const Result r = run({"compare", (dir / "image.exr").string(), (dir / "reference.exr").string(),
                          "--json", "--relmse-reject", "0.25"},
                         dir);
    ASSERT_EQ(r.status, 0) << r.errors;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["time"].get<double>(), 0.5);
    EXPECT_NEAR(j["p_eff"].get<double>(), 1 / (0.5 * j["tvi_err"].get<double>()), 1e-15);
    EXPECT_NEAR(j["relmse"].get<double>(), 0.0562550, 1e-6);
    EXPECT_EQ(j["relmse_reject_fraction"].get<double>(), 0.25);
    EXPECT_FALSE(j.contains("spp"));
}

TEST(MetricsCli, CompareWithoutATimeHasNoEfficienciesAndZeroErrorsHaveNone) {
    const fs::path dir = scratchDirectory();
    writeCase(dir, {});
    const fs::path reference = dir / "reference.exr";
    Result r = run({"compare", (dir / "image.exr").string(), reference.string(), "--json"}, dir);
    ASSERT_EQ(r.status, 0) << r.errors;
    Json j = Json::parse(r.out);
    for (const char* key : {"time", "p_eff", "mse_eff"})
        EXPECT_FALSE(j.contains(key)) << key;

    r = run({"compare", reference.string(), reference.string(), "--json", "--time", "3"}, dir);
    ASSERT_EQ(r.status, 0) << r.errors;
    j = Json::parse(r.out);
    EXPECT_TRUE(j["p_eff"].is_null());
    EXPECT_TRUE(j["mse_eff"].is_null());
    EXPECT_NE(j["note"].get<std::string>().find("tvi_err is 0"), std::string::npos);
}

TEST(MetricsCli, CompareSummaryIsReadable) {
    const fs::path dir = scratchDirectory();
    writeCase(dir, {});
    const Result r =
        run({"compare", (dir / "image.exr").string(), (dir / "reference.exr").string()}, dir);
    ASSERT_EQ(r.status, 0) << r.errors;
    EXPECT_NE(r.out.find("sigma_over_mu  0.330719"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("tvi_err        23.7455"), std::string::npos) << r.out;
}

TEST(MetricsCli, SlopeOfAPointFile) {
    const fs::path dir = scratchDirectory();
    std::ofstream(dir / "points.json") << R"({"points": [{"spp": 1, "error": 1, "time": 1},
        {"spp": 4, "error": 0.5, "time": 2}, {"spp": 16, "error": 0.25, "time": 4}]})";
    const Result r = run({"slope", (dir / "points.json").string(), "--json"}, dir);
    ASSERT_EQ(r.status, 0) << r.errors;
    const Json j = Json::parse(r.out);
    EXPECT_NEAR(j["vs_spp"]["slope"].get<double>(), -0.5, 1e-12);
    EXPECT_NEAR(j["vs_time"]["slope"].get<double>(), -1, 1e-12);
    EXPECT_NEAR(j["vs_spp"]["r2"].get<double>(), 1, 1e-12);
    EXPECT_EQ(j["vs_spp"]["n"], 3);
    for (const char* key : {"slope_stderr", "intercept"})
        EXPECT_TRUE(j["vs_spp"].contains(key)) << key;
}

TEST(MetricsCli, MergeWritesTheAverageAndItsNoise) {
    const fs::path dir = scratchDirectory();
    // test_metrics.cpp's two halves: merged (2,2,2), (5,5,7); noise rmse 1, σ/µ 6/23.
    writeRgb(dir / "a.exr", 2, 1, {{1, 2, 3}, {5, 5, 5}},
             {{"renderer.spp", 8}, {"renderer.integrator", std::string("path")}});
    writeRgb(dir / "b.exr", 2, 1, {{3, 2, 1}, {5, 5, 9}}, {{"renderer.spp", 8}});
    const fs::path out = dir / "reference.exr";
    const Result r = run({"merge", (dir / "a.exr").string(), (dir / "b.exr").string(), "--out",
                          out.string(), "--json"},
                         dir);
    ASSERT_EQ(r.status, 0) << r.errors;
    const Json j = Json::parse(r.out);
    EXPECT_EQ(j["out"], out.string());
    EXPECT_EQ(j["spp"], 16);
    EXPECT_DOUBLE_EQ(j["mean"].get<double>(), 23.0 / 6);
    EXPECT_DOUBLE_EQ(j["half_difference_rmse"].get<double>(), 2);
    EXPECT_DOUBLE_EQ(j["noise_rmse"].get<double>(), 1);
    EXPECT_DOUBLE_EQ(j["noise_sigma_over_mu"].get<double>(), 6.0 / 23);
    const ExrImage merged = readExr(out);
    EXPECT_EQ(merged.channels.at("R"), (std::vector<float>{2, 5}));
    EXPECT_EQ(merged.channels.at("B"), (std::vector<float>{2, 7}));
    EXPECT_EQ(std::get<int>(merged.attributes.at("reference.spp")), 16);
    EXPECT_EQ(std::get<std::string>(merged.attributes.at("reference.sources")),
              (dir / "a.exr").string() + "," + (dir / "b.exr").string());
    EXPECT_EQ(std::get<std::string>(merged.attributes.at("renderer.integrator")), "path");
    EXPECT_DOUBLE_EQ(std::get<double>(merged.attributes.at("reference.noiseRmse")), 1);
}

struct BadRun {
    const char* what;
    std::vector<std::string> args;  // DIR is replaced by the scratch directory
    const char* mentions;
};

void PrintTo(const BadRun& b, std::ostream* os) {
    *os << b.what;
}

class MetricsCliBadInput : public ::testing::TestWithParam<BadRun> {};

// Writes the inputs every bad run draws on.
void writeInputs(const fs::path& dir) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    writeRgb(dir / "a.exr", 2, 2, {{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}});
    writeRgb(dir / "small.exr", 1, 1, {{1, 1, 1}});
    writeRgb(dir / "nan.exr", 2, 2, {{1, 1, 1}, {1, 1, 1}, {1, nan, 1}, {1, 1, 1}});
    writeRgb(dir / "black.exr", 2, 2, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}});
    std::ofstream(dir / "text.exr") << "not an EXR file\n";
    std::ofstream(dir / "syntax.json") << "[{\"spp\": 1,, }]";
    std::ofstream(dir / "negative.json")
        << R"({"points": [{"spp": 1, "error": 1}, {"spp": 2, "error": 1}, {"spp": 4, "error": 1},
                         {"spp": 8, "error": -0.5}]})";
    std::ofstream(dir / "two.json") << R"([{"spp": 1, "error": 1}, {"spp": 2, "error": 1}])";
}

TEST_P(MetricsCliBadInput, ExitsWithStatusTwoOneMessageAndWritesNothing) {
    const fs::path dir = scratchDirectory();
    writeInputs(dir);
    std::vector<std::string> args;
    for (std::string a : GetParam().args) {
        if (a.rfind("DIR/", 0) == 0) a = (dir / a.substr(4)).string();
        args.push_back(a);
    }
    const Result r = run(args, dir);
    EXPECT_EQ(r.status, 2) << r.errors;
    EXPECT_EQ(std::count(r.errors.begin(), r.errors.end(), '\n'), 1) << r.errors;
    EXPECT_EQ(r.errors.rfind("error: ", 0), 0u) << r.errors;
    EXPECT_NE(r.errors.find(GetParam().mentions), std::string::npos) << r.errors;
    EXPECT_EQ(r.out, "");
    EXPECT_FALSE(fs::exists(dir / "out")) << "nothing may be written";
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(
    All, MetricsCliBadInput,
    ::testing::Values(
        BadRun{"missing image", {"compare", "DIR/none.exr", "DIR/a.exr"}, "none.exr: no such file"},
        BadRun{"not an EXR", {"compare", "DIR/a.exr", "DIR/text.exr"}, "text.exr"},
        BadRun{"mismatched resolution",
               {"compare", "DIR/small.exr", "DIR/a.exr"},
               "small.exr is 1x1 but the reference"},
        BadRun{"NaN pixel",
               {"compare", "DIR/a.exr", "DIR/nan.exr"},
               "nan.exr: NaN value in channel G at pixel (0, 1)"},
        BadRun{"zero-mean reference", {"compare", "DIR/a.exr", "DIR/black.exr"}, "black.exr"},
        BadRun{"reject fraction of one half",
               {"compare", "DIR/a.exr", "DIR/a.exr", "--relmse-reject", "0.5"},
               "--relmse-reject"},
        BadRun{"infinite time", {"compare", "DIR/a.exr", "DIR/a.exr", "--time", "inf"}, "--time"},
        BadRun{"malformed slope JSON", {"slope", "DIR/syntax.json"}, "syntax.json: malformed JSON"},
        BadRun{"negative error", {"slope", "DIR/negative.json"}, "/points/3/error"},
        BadRun{"too few points", {"slope", "DIR/two.json"}, "too few points"},
        BadRun{"missing point file", {"slope", "DIR/none.json"}, "none.json"},
        BadRun{"merge of different sizes",
               {"merge", "DIR/a.exr", "DIR/small.exr", "--out", "DIR/out/merged.exr"},
               "small.exr is 1x1"},
        BadRun{"merge with a NaN pixel",
               {"merge", "DIR/a.exr", "DIR/nan.exr", "--out", "DIR/out/merged.exr"},
               "pixel (0, 1)"},
        BadRun{"merge of one image", {"merge", "DIR/a.exr", "--out", "DIR/out/m.exr"}, "inputs"},
        BadRun{"unknown option", {"compare", "DIR/a.exr", "DIR/a.exr", "--jsn"}, "--jsn"}),
    [](const ::testing::TestParamInfo<BadRun>& param) {
        std::string name = param.param.what;
        for (char& c : name)
            if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
        return name;
    });

}  // namespace
}  // namespace rr::test
