// Two-stage sampling's density (Cline et al. 2006 §2–3, Appendix A) at fixed shading points, for
// each material the paper names and others with analytic peaks, on a synthetic lat-long map and
// on Galileo's probe resampled to lat-long at load:
//  - warped points follow the density the warp reports: χ² over cells of texels (the density is
//    constant inside a texel, so a cell's expected count is exact), with a negative control;
//  - warp() and densityAt() agree on every warped point's density;
//  - the texel densities sum to one, and p_ω integrates to one over the sphere (z-test of
//    E[4π p_ω] under uniform directions), which the appendix's printed multiplication by the
//    Jacobian fails (negative control);
//  - with radiance and f constant p_ω is 1/4π (the Jacobian divides);
//  - every direction where Le·f > 0 has p_ω > 0 (the partition's floor);
//  - a probe resampled with `latlong_width` is the light escaped rays see.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "loader/factories.h"
#include "sampling/warps.h"
#include "scene/lights/environment_map.h"
#include "support/chi2.h"
#include "support/maps.h"
#include "support/scene_testing.h"
#include "support/scratch.h"
#include "support/test_random.h"
#include "techniques/two_stage/hierarchical_warp.h"
#include "techniques/two_stage/two_stage_estimator.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;
using two_stage::Partition;
using two_stage::TwoStageEstimator;
using two_stage::TwoStageSettings;

constexpr double kPiD = std::numbers::pi;

// --- Maps ---------------------------------------------------------------------------------------

// A 128 × 64 lat-long map: a smooth sky, a bright sun of 3 × 2 texels, a black band (zero
// radiance) and a dim floor, so that the partition sees structure at several scales.
constexpr int kMapWidth = 128, kMapHeight = 64;
Rgb syntheticTexel(int col, int row) {
    if (col >= 40 && col < 43 && row >= 20 && row < 22) return Rgb(800, 700, 600);
    if (row >= 30 && row < 34) return Rgb(0.0f);
    if (row >= 34) return Rgb(0.05f, 0.04f, 0.03f);
    const double s = double(col) / kMapWidth, t = double(row) / kMapHeight;
    return Rgb(float(0.5 + 0.4 * std::sin(2 * kPiD * s)), float(0.6 + 0.3 * t), 0.8f);
}

std::unique_ptr<EnvironmentMap> loadMap(const Json& description) {
    ObjectReader reader(description, "/lights/0");
    std::unique_ptr<Light> light =
        makeLight(reader, AssetResolver::standard(TEST_SCENES_DIR), Transform());
    auto* map = dynamic_cast<EnvironmentMap*>(light.release());
    EXPECT_NE(map, nullptr);
    map->preprocess(Vec3(0.0f), 1.0f);
    return std::unique_ptr<EnvironmentMap>(map);
}

fs::path writeSyntheticMap() {
    return writeRgbExr(scratchDirectory() / "synthetic_latlong.exr", kMapWidth, kMapHeight,
                       syntheticTexel);
}

std::unique_ptr<EnvironmentMap> syntheticMap() {
    return loadMap(Json{
        {"type", "environment"}, {"file", writeSyntheticMap().string()}, {"layout", "latlong"}});
}

// Galileo's probe at a quarter of the figures' resolution (256 × 128), or nullptr when the
// asset is not on the search path.
std::unique_ptr<EnvironmentMap> galileoMap() {
    if (!AssetResolver::standard(TEST_SCENES_DIR).resolve("envmaps/galileo_probe.hdr"))
        return nullptr;
    return loadMap(Json{{"type", "environment"},
                        {"file", "envmaps/galileo_probe.hdr"},
                        {"layout", "probe"},
                        {"latlong_width", 256}});
}

// --- A shading point of the test's own ---------------------------------------------------------

// A surface point whose scattering is a material at a fixed frame and viewing direction (or any
// function), lit by nothing but what the estimator asks of it.
class FixedPoint final : public ShadingPoint {
  public:
    using Scattering = std::function<Rgb(const Vec3& wi)>;

    FixedPoint(ScatteringShape shape, Scattering scattering)
        : shape_(std::move(shape)), scattering_(std::move(scattering)) {}

    static FixedPoint onMaterial(const Material& material, const Frame& frame, const Vec3& wo) {
        static const ShadingContext ctx{};
        const Vec3 woLocal = frame.toLocal(wo);
        ScatteringShape shape;
        shape.normal = woLocal.z < 0 ? -frame.n : frame.n;
        shape.transmits = material.hasTransmission();
        LobePeaks local;
        lobePeakSource(material)->peaks(ctx, woLocal, &local);
        for (int i = 0; i < local.count; ++i)
            shape.peaks.add(frame.toWorld(local.directions[i]));
        FixedPoint point(shape, [&material, frame, woLocal](const Vec3& wi) {
            return material.eval(ctx, woLocal, frame.toLocal(wi));
        });
        point.material_ = &material;
        point.frame_ = frame;
        point.woLocal_ = woLocal;
        return point;
    }

    bool sampleLight(uint32_t, uint32_t, const LightStandIns*, LightSample*, float*,
                     const Light**) override {
        return false;
    }
    Rgb scattering(const Vec3& wi) const override { return scattering_(wi); }
    float scatteringPdf(const Vec3&) const override { return 0; }
    float scatteringSamples() const override { return 0; }
    Rgb visibility(const LightSample&, bool, float* survival) override {
        *survival = 1;
        return Rgb(1.0f);
    }
    Rgb contribution(const Rgb& f, const Rgb& le, const Rgb& tr, float misWeight,
                     float density) const override {
        return f * le * tr * (misWeight / density);
    }
    float decide1D(Decision d, uint32_t repeat, uint32_t) const override {
        return uniform(uint64_t(d.id), repeat);
    }
    Vec2 decide2D(Decision d, uint32_t repeat, uint32_t) const override {
        return uniform2(uint64_t(d.id) + 100, repeat);
    }
    const Frame* frame() const override { return &frame_; }
    Vec3 position() const override { return Vec3(0.0f); }
    bool scatteringShape(const LobePeakSources*, ScatteringShape* out) const override {
        *out = shape_;
        return true;
    }
    bool sampleScattering(float uLobe, const Vec2& u, Vec3* wi, float* pdf) const override {
        static const ShadingContext ctx{};
        BsdfSample bs;
        if (!material_ || !material_->sample(ctx, woLocal_, uLobe, u, &bs) || bs.isSpecular())
            return false;
        *wi = frame_.toWorld(bs.wi);
        *pdf = bs.pdf;
        return true;
    }
    float sampleScatteringPdf(const Vec3& wi) const override {
        static const ShadingContext ctx{};
        return material_ ? material_->pdf(ctx, woLocal_, frame_.toLocal(wi)) : 0.0f;
    }
    using ShadingPoint::incidentEmission;
    Rgb incidentEmission(const Vec3&, EmissionSource*) override { return Rgb(0.0f); }
    bool sampleLightOf(const Light&, const Vec2&, LightSample*) const override { return false; }
    float infiniteLightPdf(const Vec3&, Rgb* radiance) const override {
        *radiance = Rgb(0.0f);
        return 0;
    }
    void add(const Rgb& contribution) override { sum_ += contribution; }

  private:
    ScatteringShape shape_;
    Scattering scattering_;
    const Material* material_ = nullptr;
    Frame frame_;
    Vec3 woLocal_;
    Rgb sum_{0.0f};
};

// --- Cases --------------------------------------------------------------------------------------

struct MaterialCase {
    const char* name;
    const char* json;
};
const MaterialCase kMaterials[] = {
    {"lambert", R"({"type":"lambert","albedo":0.8})"},
    {"oren_nayar", R"({"type":"oren_nayar","albedo":0.8,"sigma":30})"},
    {"blinn", R"({"type":"blinn","reflectance":1,"roughness":0.02,"ior":1.5})"},
    {"phong", R"({"type":"phong","diffuse":0.2,"specular":0.7,"exponent":200})"},
    {"ashikhmin", R"({"type":"ashikhmin_shirley","diffuse":0.1,"specular":0.6,)"
                  R"("roughness_u":0.001,"roughness_v":1.0})"},
    {"lafortune_skin", R"({"type":"lafortune","preset":"skin"})"},
};

// Shading points in the map's frame (+Y is the map's top row, −Z its seam): a generic one, a
// normal near the pole, a normal on the seam; each with a tangent for the anisotropic material.
struct PointCase {
    const char* name;
    Vec3 normal, tangent, wo;
};
const PointCase kPoints[] = {
    {"generic", normalize(Vec3(0.3f, 0.5f, 0.8f)), Vec3(1, 0, 0),
     normalize(Vec3(-0.2f, 0.9f, 0.4f))},
    {"near_pole", normalize(Vec3(0.01f, 1.0f, 0.005f)), Vec3(1, 0, 0),
     normalize(Vec3(0.6f, 0.7f, 0.1f))},
    {"on_seam", normalize(Vec3(0.001f, 0.2f, -1.0f)), Vec3(0, 1, 0),
     normalize(Vec3(0.5f, 0.3f, -0.8f))},
};

constexpr uint32_t kSamplesPerPoint = 16;  // the estimator's N: N refinement splits
constexpr int kWarps = 200000;
constexpr int kCellSide = 4;  // texels per χ² cell side

// Every χ² run: materials × points × 2 maps, and one negative control.
const int kChi2Runs = int(std::size(kMaterials) * std::size(kPoints)) * 2 + 1;
const Chi2Family kChi2(kChi2Runs);

Frame frameOf(const PointCase& p) {
    return Frame::fromNormalAndTangent(p.normal, p.tangent);
}

std::unique_ptr<TwoStageEstimator> estimatorOn(const EnvironmentMap& map,
                                               TwoStageSettings settings = {}) {
    if (settings.samples == 1) settings.samples = kSamplesPerPoint;
    auto e = std::make_unique<TwoStageEstimator>(settings);
    e->attach(map);
    return e;
}

// Expected warps per cell of kCellSide² texels: the density is constant in a texel.
std::vector<double> expectedCounts(const Partition& partition, const EnvironmentMap& map,
                                   const two_stage::SummedAreaTable& table, double total,
                                   std::vector<double>* perCellDensity = nullptr) {
    const int cols = map.width() / kCellSide, rows = map.height() / kCellSide;
    std::vector<double> expected(size_t(cols) * rows, 0.0);
    const double texelArea = 1.0 / (double(map.width()) * map.height());
    for (int y = 0; y < map.height(); ++y)
        for (int x = 0; x < map.width(); ++x)
            expected[size_t(y / kCellSide) * cols + x / kCellSide] +=
                two_stage::densityAt(partition, table, x + 0.5, y + 0.5) * texelArea * total;
    if (perCellDensity) *perCellDensity = expected;
    return expected;
}

struct WarpTally {
    std::vector<double> counts;
    double largestDensityMismatch = 0;
};

WarpTally warpMany(const TwoStageEstimator& e, const Partition& partition, uint64_t seed) {
    const EnvironmentMap& map = e.map();
    const int cols = map.width() / kCellSide;
    WarpTally tally;
    tally.counts.assign(size_t(cols) * (map.height() / kCellSide), 0.0);
    for (int i = 0; i < kWarps; ++i) {
        two_stage::WarpedPoint p;
        if (!two_stage::warp(partition, e.table(), uniform(seed, i, 0), uniform(seed, i, 1), &p))
            continue;
        const int x = std::min(int(p.x), map.width() - 1), y = std::min(int(p.y), map.height() - 1);
        tally.counts[size_t(y / kCellSide) * cols + x / kCellSide] += 1;
        const double again = two_stage::densityAt(partition, e.table(), p.x, p.y);
        tally.largestDensityMismatch =
            std::max(tally.largestDensityMismatch, std::abs(again - p.density) / p.density);
    }
    return tally;
}

void checkPoint(const EnvironmentMap& map, const MaterialCase& m, const PointCase& pc,
                const std::string& mapName) {
    const std::string what = mapName + "/" + m.name + "/" + pc.name;
    const auto mat = materialFromJson(m.json);
    FixedPoint point = FixedPoint::onMaterial(*mat, frameOf(pc), pc.wo);
    const auto e = estimatorOn(map);
    Partition partition;
    ASSERT_TRUE(e->partitionAt(point, &partition)) << what;

    // The texel densities sum to one.
    double total = 0;
    for (double c : expectedCounts(partition, map, e->table(), 1.0))
        total += c;
    EXPECT_NEAR(total, 1.0, 1e-9) << what;

    const WarpTally tally = warpMany(*e, partition, 0x2570 + uint64_t(pc.normal.x * 1e6));
    EXPECT_LT(tally.largestDensityMismatch, 1e-9) << what;
    double warped = 0;
    for (double c : tally.counts)
        warped += c;
    EXPECT_EQ(warped, kWarps) << what << ": some warps yielded no point";
    kChi2.expectFits(
        chi2GoodnessOfFit(tally.counts, expectedCounts(partition, map, e->table(), warped)), what);

    // Support: uniform directions where Le·f > 0 have p_ω > 0.
    int uncovered = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 w = squareToUniformSphere(uniform2(77, i));
        const Rgb le = map.escapedRadiance(w);
        if (le.isBlack() || !(point.scattering(w).luminance() > 0)) continue;
        if (!(e->pdf(partition, w) > 0)) ++uncovered;
    }
    EXPECT_EQ(uncovered, 0) << what << ": directions with Le·f > 0 and no density";
}

TEST(TwoStageSampling, WarpsFollowTheirDensityOnASyntheticMap) {
    const auto map = syntheticMap();
    for (const MaterialCase& m : kMaterials)
        for (const PointCase& p : kPoints)
            checkPoint(*map, m, p, "synthetic");
}

TEST(TwoStageSampling, WarpsFollowTheirDensityOnGalileo) {
    const auto map = galileoMap();
    if (!map) GTEST_SKIP() << "envmaps/galileo_probe.hdr is not on the asset search path";
    for (const MaterialCase& m : kMaterials)
        for (const PointCase& p : kPoints)
            checkPoint(*map, m, p, "galileo");
}

// Fig. 3: the initial partition splits the root at the normal's grid point and at the column
// half a turn away, six regions in three columns and two rows (f constant: no cascade, no
// refinement).
TEST(TwoStagePartition, InitialPartitionIsSixRegions) {
    const auto map = syntheticMap();
    const two_stage::SummedAreaTable table(*map);
    struct Constant final : two_stage::ProductFactor {
        double at(int, int) const override { return 1; }
    } f;
    two_stage::PartitionRequest request;
    request.rootY0 = 10;
    request.rootY1 = 42;
    request.normalX = 100;  // the column half a turn away, 164, wraps to 36
    request.normalY = 26;
    Partition partition;
    partition.build(table, request, f);
    partition.finish();
    std::set<std::array<int, 4>> leaves;
    for (int i = 0; i < int(partition.stats().regions); ++i) {
        const two_stage::Region& r = partition.region(i);
        if (r.isLeaf()) leaves.insert({r.x0, r.y0, r.x1, r.y1});
    }
    const std::set<std::array<int, 4>> expected = {{0, 10, 36, 26},    {36, 10, 100, 26},
                                                   {100, 10, 128, 26}, {0, 26, 36, 42},
                                                   {36, 26, 100, 42},  {100, 26, 128, 42}};
    EXPECT_EQ(leaves, expected);
}

// A χ² that cannot tell the warp from a plausible bug is blind: the density of a warp that
// stopped at the partition's leaves (uniform inside each leaf, without the virtual regions that
// follow the map below them) must be rejected.
TEST(TwoStageSampling, NegativeControlLeafUniformDensityIsRejected) {
    const auto map = syntheticMap();
    const auto mat = materialFromJson(kMaterials[0].json);
    FixedPoint point = FixedPoint::onMaterial(*mat, frameOf(kPoints[0]), kPoints[0].wo);
    const auto e = estimatorOn(*map);
    Partition partition;
    ASSERT_TRUE(e->partitionAt(point, &partition));
    const WarpTally tally = warpMany(*e, partition, 99);
    const int cols = map->width() / kCellSide;
    std::vector<double> expected(tally.counts.size(), 0.0);
    for (int y = 0; y < map->height(); ++y)
        for (int x = 0; x < map->width(); ++x) {
            const two_stage::Region& leaf = partition.region(partition.leafAt(x, y));
            if (y < partition.root().y0 || y >= partition.root().y1) continue;
            expected[size_t(y / kCellSide) * cols + x / kCellSide] +=
                kWarps * leaf.weight / partition.root().weight / double(leaf.area());
        }
    kChi2.expectRejects(chi2GoodnessOfFit(tally.counts, expected), "leaf-uniform density");
}

// ∫ p_ω dω = 1: E[4π p_ω(ω)] over uniform directions, z-tested; the appendix's printed last
// line (prob·cos φ / 2π² instead of prob / (2π² cos φ)) must fail the same test.
TEST(TwoStageSampling, SolidAngleDensityIntegratesToOne) {
    const auto map = syntheticMap();
    const auto mat = materialFromJson(kMaterials[0].json);  // Lambert: a broad product
    FixedPoint point = FixedPoint::onMaterial(*mat, frameOf(kPoints[0]), kPoints[0].wo);
    const auto e = estimatorOn(*map);
    Partition partition;
    ASSERT_TRUE(e->partitionAt(point, &partition));
    constexpr int kDirections = 400000;
    double sum = 0, sumSq = 0, printedSum = 0, printedSumSq = 0;
    for (int i = 0; i < kDirections; ++i) {
        const Vec3 w = squareToUniformSphere(uniform2(5, i));
        const double v = 4 * kPiD * e->pdf(partition, w);
        sum += v;
        sumSq += v * v;
        // The printed formula: the density per image area times the Jacobian over (2π²)².
        const Vec2 st = map->layout().imagePoint(map->toWorld().toLocal(w));
        const double jacobian = map->layout().jacobian(st);
        const double printed =
            v / (4 * kPiD) * jacobian * jacobian / (4 * std::pow(kPiD, 4)) * 4 * kPiD;
        printedSum += printed;
        printedSumSq += printed * printed;
    }
    const double z = zThreshold(sidakAlpha(0.01, 2));
    auto zScore = [&](double s, double s2) {
        const double mean = s / kDirections;
        const double variance = (s2 / kDirections - mean * mean) / (kDirections - 1);
        return (mean - 1) / std::sqrt(variance);
    };
    EXPECT_LT(std::abs(zScore(sum, sumSq)), z) << "mean " << sum / kDirections;
    EXPECT_GT(std::abs(zScore(printedSum, printedSumSq)), z)
        << "the printed formula integrates to " << printedSum / kDirections;
}

// With L and f constant the density per steradian is 1/4π, up to the table's cos(latitude)
// taken at each row's centre: exactly p_ω = H sin θ_row / (Σ_rows sin θ_r · 2π² sin θ) at the
// point's own θ. A Jacobian that multiplied instead of dividing would be off by orders.
TEST(TwoStageSampling, ConstantProductGivesOneOverFourPi) {
    constexpr int kWidth = 64, kHeight = 32;
    const fs::path file = writeRgbExr(scratchDirectory() / "constant.exr", kWidth, kHeight,
                                      [](int, int) { return Rgb(1.0f); });
    const auto map =
        loadMap(Json{{"type", "environment"}, {"file", file.string()}, {"layout", "latlong"}});
    ScatteringShape shape;
    shape.normal = Vec3(0, 0, 1);
    shape.transmits = true;  // the root is the whole map
    FixedPoint point(shape, [](const Vec3&) { return Rgb(1.0f); });
    const auto e = estimatorOn(*map);
    Partition partition;
    ASSERT_TRUE(e->partitionAt(point, &partition));
    double rowSines = 0;
    for (int r = 0; r < kHeight; ++r)
        rowSines += std::sin(kPiD * (r + 0.5) / kHeight);
    double largestRatio = 0;
    for (int i = 0; i < 10000; ++i) {
        Vec3 w;
        int col, row;
        double pdf;
        ASSERT_TRUE(
            e->warpDirection(partition, uniform(3, i, 0), uniform(3, i, 1), &w, &col, &row, &pdf));
        if (row == 0 || row == kHeight - 1) continue;  // θ from a float direction at the poles
        const double theta = kPiD * map->layout().imagePoint(map->toWorld().toLocal(w)).y;
        const double expected = kHeight * std::sin(kPiD * (row + 0.5) / kHeight) /
                                (rowSines * 2 * kPiD * kPiD * std::sin(theta));
        EXPECT_NEAR(pdf / expected, 1.0, 1e-3) << "row " << row;
        largestRatio = std::max(largestRatio, std::abs(pdf * 4 * kPiD - 1));
    }
    // Away from the poles, within a row's variation of sin θ.
    EXPECT_LT(largestRatio, 0.6);
}

// A probe resampled with latlong_width is one light: what escaped rays see is the lat-long
// texel the two-stage table is built on, and its radiance integral stays the probe's.
TEST(TwoStageSampling, ResampledProbeIsTheLightEveryTechniqueSees) {
    const auto map = galileoMap();
    if (!map) GTEST_SKIP() << "envmaps/galileo_probe.hdr is not on the asset search path";
    ASSERT_NE(dynamic_cast<const LatLongLayout*>(&map->layout()), nullptr);
    for (int row = 0; row < map->height(); row += 7)
        for (int col = 0; col < map->width(); col += 5) {
            Vec3 local;
            float jacobian;
            map->layout().direction({(col + 0.5f) / map->width(), (row + 0.5f) / map->height()},
                                    &local, &jacobian);
            const Rgb seen = map->escapedRadiance(map->toWorld().toWorld(local));
            ASSERT_EQ(seen.r, map->texel(col, row).r) << col << "," << row;
        }
    const auto probe = loadMap(
        Json{{"type", "environment"}, {"file", "envmaps/galileo_probe.hdr"}, {"layout", "probe"}});
    EXPECT_NEAR(map->radianceIntegral().luminance() / probe->radianceIntegral().luminance(), 1.0,
                0.03);
}

}  // namespace
}  // namespace rr::test
