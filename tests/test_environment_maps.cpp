// Environment maps (scene/lights/environment_map.h, env_layout.h): the layouts' conventions and
// Jacobians, sampling (χ² of directions) against directionPdf(), the pdf's normalisation, the
// probe's mask, rotation, power, and renders of a constant map that must give albedo·L.
// Two kinds of map: small sparse synthetic ones (a few bright texels on black, written to a
// scratch EXR) and Debevec's Galileo probe from the asset search path (skipped when absent,
// unless REQUIRE_ASSETS=1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "io/exr_io.h"
#include "io/rgb_image_io.h"
#include "loader/factories.h"
#include "scene/lights/environment_map.h"
#include "support/chi2.h"
#include "support/histograms.h"
#include "support/maps.h"
#include "support/mean_agreement.h"
#include "support/scene_testing.h"
#include "support/scratch.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

// Every χ² run in this file: the sparse synthetic map in both layouts (2), Galileo in both
// layouts (2), and one negative control.
constexpr int kRuns = 5;
const Chi2Family kChi2(kRuns);
constexpr int kSamples = 1000000;

// Every z-test of the constant-map renders: 2 layouts × 2 integrators × (3 channels + 16
// blocks), Šidák-corrected to a family-wise level of 0.01.
constexpr int kComparisons = 76;
const double kZ = zThreshold(sidakAlpha(0.01, kComparisons));

// --- Maps ---------------------------------------------------------------------------------------

fs::path writeMap(const std::string& name, int width, int height, const PixelFunction& pixel) {
    return writeRgbExr(scratchDirectory() / name, width, height, pixel);
}

// The light an "environment" object describes (built by the light factory, as a scene would),
// in a scene of radius 1.
std::unique_ptr<EnvironmentMap> loadMap(const Json& description) {
    ObjectReader reader(description, "/lights/0");
    std::unique_ptr<Light> light =
        makeLight(reader, AssetResolver::standard(TEST_SCENES_DIR), Transform());
    auto* map = dynamic_cast<EnvironmentMap*>(light.get());
    EXPECT_NE(map, nullptr);
    light.release();
    map->preprocess(Vec3(0.0f), 1.0f);
    return std::unique_ptr<EnvironmentMap>(map);
}

std::unique_ptr<EnvironmentMap> loadMap(const fs::path& file, const std::string& layout) {
    return loadMap(Json{{"type", "environment"}, {"file", file.string()}, {"layout", layout}});
}

// Sparse maps: a few bright texels on a background 10⁴ times dimmer (not black, so that a
// draw rounded across the edge of a bright texel lands where the density is not zero). The
// lat-long map has a bright texel at the +Y pole on the seam; the probe map has one on its rim
// (part of that texel is outside the disc: draws there are refused) and two that must be
// masked: one in the corner, one whose centre is just outside the disc though a corner of it
// is inside.
constexpr int kLatLongWidth = 16, kLatLongHeight = 8, kProbeSize = 16;
const Rgb kBackground(0.002f);
Rgb sparseLatLong(int col, int row) {
    if (col == 0 && row == 0) return Rgb(40, 30, 20);
    if (col == 5 && row == 3) return Rgb(5);
    if (col == 11 && row == 6) return Rgb(1, 2, 8);
    if (col == 15 && row == 4) return Rgb(20, 1, 1);
    return kBackground;
}
Rgb sparseProbe(int col, int row) {
    if (col == 8 && row == 8) return Rgb(10);
    if (col == 3 && row == 7) return Rgb(2, 3, 4);
    if (col == 12 && row == 3) return Rgb(6, 1, 1);
    if (col == 0 && row == 7) return Rgb(8, 8, 1);   // on the rim
    if (col == 15 && row == 0) return Rgb(100);      // corner: masked
    if (col == 0 && row == 4) return Rgb(50, 1, 1);  // centre outside the disc: masked
    return kBackground;
}

struct SparseMap {
    const char* layout;
    int width, height;
    Rgb (*pixel)(int, int);
};
const SparseMap kSparseMaps[] = {{"latlong", kLatLongWidth, kLatLongHeight, sparseLatLong},
                                 {"probe", kProbeSize, kProbeSize, sparseProbe}};

std::optional<fs::path> galileo() {
    return AssetResolver::standard(TEST_SCENES_DIR).resolve("envmaps/galileo_probe.hdr");
}
bool assetsRequired() {
    const char* v = std::getenv("REQUIRE_ASSETS");
    return v != nullptr && std::string(v) == "1";
}

// Tests that need the Galileo probe: skipped when it is not on the asset search path.
class GalileoProbe : public ::testing::TestWithParam<std::string> {
  protected:
    void SetUp() override {
        file_ = galileo();
        if (file_) return;
        const std::string where = AssetResolver::standard(TEST_SCENES_DIR).describe();
        if (assetsRequired())
            FAIL() << "REQUIRE_ASSETS=1 but no envmaps/galileo_probe.hdr in " << where;
        GTEST_SKIP() << "envmaps/galileo_probe.hdr is not on the asset search path " << where;
    }
    std::optional<fs::path> file_;
};

// --- Layout conventions -------------------------------------------------------------------------

Vec3 directionAt(const EnvLayout& layout, Vec2 st) {
    Vec3 w;
    float jacobian;
    EXPECT_TRUE(layout.direction(st, &w, &jacobian));
    return w;
}

void expectDirection(const Vec3& w, const Vec3& expected, const std::string& what) {
    EXPECT_NEAR(w.x, expected.x, 1e-5f) << what;
    EXPECT_NEAR(w.y, expected.y, 1e-5f) << what;
    EXPECT_NEAR(w.z, expected.z, 1e-5f) << what;
}

// The documented convention: image centre +Z, +Y up, image right −X (the viewer's right when
// facing +Z), for both layouts.
TEST(EnvLayouts, FollowTheDocumentedConvention) {
    const LatLongLayout latlong;
    expectDirection(directionAt(latlong, {0.5f, 0.5f}), Vec3(0, 0, 1), "latlong centre");
    expectDirection(directionAt(latlong, {0.75f, 0.5f}), Vec3(-1, 0, 0), "latlong s = 3/4");
    expectDirection(directionAt(latlong, {0.25f, 0.5f}), Vec3(1, 0, 0), "latlong s = 1/4");
    expectDirection(directionAt(latlong, {0.0f, 0.5f}), Vec3(0, 0, -1), "latlong left edge");
    expectDirection(directionAt(latlong, {0.3f, 0.0f}), Vec3(0, 1, 0), "latlong top row");
    expectDirection(directionAt(latlong, {0.3f, 1.0f}), Vec3(0, -1, 0), "latlong bottom row");
    const ProbeLayout probe;
    expectDirection(directionAt(probe, {0.5f, 0.5f}), Vec3(0, 0, 1), "probe centre");
    // ρ = ½ is θ = 90°: right of the centre is −X, above it +Y.
    expectDirection(directionAt(probe, {0.75f, 0.5f}), Vec3(-1, 0, 0), "probe u = 1/2");
    expectDirection(directionAt(probe, {0.5f, 0.25f}), Vec3(0, 1, 0), "probe v = 1/2");
    expectDirection(directionAt(probe, {1.0f, 0.5f}), Vec3(0, 0, -1), "probe rim");
    Vec3 w;
    float jacobian;
    EXPECT_FALSE(probe.direction({0.95f, 0.95f}, &w, &jacobian)) << "probe corner";
    EXPECT_EQ(probe.jacobian({0.95f, 0.95f}), 0.0f);
}

// imagePoint inverts direction, and the Jacobian matches finite differences of the map:
// dω/(ds dt) = |∂w/∂s × ∂w/∂t|.
TEST(EnvLayouts, ImagePointInvertsDirectionAndJacobianIsTheAreaRatio) {
    const LatLongLayout latlong;
    const ProbeLayout probe;
    for (const EnvLayout* layout :
         {static_cast<const EnvLayout*>(&latlong), static_cast<const EnvLayout*>(&probe)}) {
        for (int i = 0; i < 2000; ++i) {
            const Vec2 st(0.02f + 0.96f * uniform(3, i, 0), 0.02f + 0.96f * uniform(3, i, 1));
            Vec3 w;
            float jacobian;
            if (!layout->direction(st, &w, &jacobian)) continue;
            if (layout == &probe &&
                (2 * st.x - 1) * (2 * st.x - 1) + (1 - 2 * st.y) * (1 - 2 * st.y) > 0.96f)
                continue;  // near the rim, where the map is singular
            EXPECT_NEAR(length(w), 1.0f, 1e-5f);
            const Vec2 back = layout->imagePoint(w);
            EXPECT_NEAR(back.x, st.x, 2e-5f) << st.x << ", " << st.y;
            EXPECT_NEAR(back.y, st.y, 2e-5f) << st.x << ", " << st.y;
            const double h = 1e-3;
            Vec3 ws0, ws1, wt0, wt1;
            float j;
            layout->direction({float(st.x - h), st.y}, &ws0, &j);
            layout->direction({float(st.x + h), st.y}, &ws1, &j);
            layout->direction({st.x, float(st.y - h)}, &wt0, &j);
            layout->direction({st.x, float(st.y + h)}, &wt1, &j);
            const double area = length(cross(ws1 - ws0, wt1 - wt0)) / (4 * h * h);
            EXPECT_NEAR(jacobian, area, 2e-3 * area + 1e-3) << st.x << ", " << st.y;
            EXPECT_FLOAT_EQ(layout->jacobian(st), jacobian);
        }
    }
}

// Σ over texels of dω/(ds dt) at the centre × texel area = 4π: the probe at Galileo's 1000²
// over the texels whose centre is in the disc (the ones the map keeps), and a lat-long map.
TEST(EnvLayouts, TexelSolidAnglesSumToFourPi) {
    struct Case {
        std::unique_ptr<EnvLayout> layout;
        int width, height;
    };
    Case cases[] = {{makeEnvLayout("probe"), 1000, 1000}, {makeEnvLayout("latlong"), 512, 256}};
    for (const Case& c : cases) {
        double sum = 0;
        for (int row = 0; row < c.height; ++row)
            for (int col = 0; col < c.width; ++col)
                sum += c.layout->jacobian({(col + 0.5f) / c.width, (row + 0.5f) / c.height});
        sum /= double(c.width) * c.height;
        EXPECT_NEAR(sum, 4 * M_PI, 1e-3 * 4 * M_PI) << c.width << "x" << c.height;
    }
    EXPECT_EQ(makeEnvLayout("cube"), nullptr);
}

// --- The documented conventions, restated independently of env_layout.cpp -----------------------

constexpr double kPiD = M_PI;

// The unit direction at image point (s, t); false outside the layout's domain (probe corners).
bool documentedDirection(const std::string& layout, double s, double t, Vec3* w) {
    if (layout == "latlong") {
        const double theta = kPiD * t, phi = 2 * kPiD * s;
        *w = Vec3(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)),
                  float(-std::sin(theta) * std::cos(phi)));
        return true;
    }
    const double u = 2 * s - 1, v = 1 - 2 * t, rho = std::hypot(u, v);
    if (rho > 1) return false;
    const double radial = rho > 0 ? std::sin(kPiD * rho) / rho : kPiD;
    *w = Vec3(float(-radial * u), float(radial * v), float(std::cos(kPiD * rho)));
    return true;
}

// The image point (s, t) of a unit direction.
Vec2 documentedImagePoint(const std::string& layout, const Vec3& w) {
    const double x = w.x, y = w.y, z = w.z;
    if (layout == "latlong") {
        double phi = std::atan2(x, -z);
        if (phi < 0) phi += 2 * kPiD;
        return {float(phi / (2 * kPiD)), float(std::atan2(std::hypot(x, z), y) / kPiD)};
    }
    const double d = std::hypot(x, y), rho = std::atan2(d, z) / kPiD;
    const double u = d > 0 ? -x / d * rho : rho, v = d > 0 ? y / d * rho : 0;
    return {float((u + 1) / 2), float((1 - v) / 2)};
}

// dω/(ds dt): 2π² sin(πt) (lat-long); 4π sin(πρ)/ρ inside the disc (probe).
double documentedJacobian(const std::string& layout, double s, double t) {
    if (layout == "latlong") return 2 * kPiD * kPiD * std::sin(kPiD * t);
    const double rho = std::hypot(2 * s - 1, 1 - 2 * t);
    if (rho >= 1) return 0;
    return rho > 0 ? 4 * kPiD * std::sin(kPiD * rho) / rho : 4 * kPiD * kPiD;
}

// A texel's solid angle over its area: the mean of the documented Jacobian over a k × k grid.
double texelJacobian(const std::string& layout, int width, int height, int col, int row, int k) {
    double sum = 0;
    for (int a = 0; a < k; ++a)
        for (int b = 0; b < k; ++b)
            sum += documentedJacobian(layout, (col + (a + 0.5) / k) / width,
                                      (row + (b + 0.5) / k) / height);
    return sum / (k * k);
}

// The fraction of texel (col, row) inside the layout's domain: for the probe, the area of the
// texel's square [u0, u1] × [v0, v1] inside the unit disc, ∫ |[v0, v1] ∩ [−h(u), h(u)]| du with
// h(u) = √(1 − u²) (midpoint rule, 4096 points, for texels with a corner outside the disc).
double insideFraction(const std::string& layout, int width, int height, int col, int row) {
    if (layout == "latlong") return 1;
    const double u0 = 2.0 * col / width - 1, u1 = 2.0 * (col + 1) / width - 1;
    const double v0 = 1 - 2.0 * (row + 1) / height, v1 = 1 - 2.0 * row / height;
    const double far =
        std::hypot(std::max(std::abs(u0), std::abs(u1)), std::max(std::abs(v0), std::abs(v1)));
    if (far <= 1) return 1;
    constexpr int kPoints = 4096;
    double area = 0;
    for (int k = 0; k < kPoints; ++k) {
        const double u = u0 + (k + 0.5) / kPoints * (u1 - u0);
        const double h = std::sqrt(std::max(0.0, 1 - u * u));
        area += std::max(0.0, std::min(v1, h) - std::max(v0, -h));
    }
    return area / kPoints / (v1 - v0);
}

// The probability of texel (col, row) under a solid-angle density `pdf` that is p/J within the
// texel (what the map claims): pdf at the centre's direction × J there × the texel's area, for
// the part of the texel inside the domain.
double texelMass(const std::string& layout, int width, int height, int col, int row,
                 const std::function<double(const Vec3&)>& pdf) {
    const double s = (col + 0.5) / width, t = (row + 0.5) / height;
    Vec3 w;
    if (!documentedDirection(layout, s, t, &w)) return 0;
    return pdf(w) * documentedJacobian(layout, s, t) / (double(width) * height) *
           insideFraction(layout, width, height, col, row);
}

// ∫ pdf dω over the sphere, by the midpoint rule over the image with k × k points per texel
// and dω = J ds dt (the documented Jacobian: sin θ dθ dφ for the lat-long map, π sin(πρ)/ρ du dv
// for the probe); a texel crossing the probe's rim counts the mean over its points inside the
// disc times its area inside (insideFraction). The cells are the texels' own, so a density
// that is p/J within each texel, as claimed, is integrated exactly, where a direction-space
// grid would err by O(h) at every texel edge and near the points where J → 0 and the density is
// unbounded (the lat-long poles, the probe's rim).
double sphereIntegral(const std::function<double(const Vec3&)>& pdf, const std::string& layout,
                      int width, int height, int k) {
    double sum = 0;
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            double texel = 0;
            int inside = 0;
            for (int a = 0; a < k; ++a)
                for (int b = 0; b < k; ++b) {
                    const double s = (col + (a + 0.5) / k) / width;
                    const double t = (row + (b + 0.5) / k) / height;
                    Vec3 w;
                    if (!documentedDirection(layout, s, t, &w)) continue;
                    texel += pdf(w) * documentedJacobian(layout, s, t);
                    ++inside;
                }
            if (inside > 0) sum += texel / inside * insideFraction(layout, width, height, col, row);
        }
    return sum / (double(width) * height);
}

// The mass of the draws sample() refuses: the parts of texels outside the domain.
double refusedMass(const EnvironmentMap& map, const std::string& layout, int width, int height) {
    const auto pdf = [&](const Vec3& w) { return double(map.directionPdf(Vec3(0.0f), w)); };
    double refused = 0;
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const double inside = insideFraction(layout, width, height, col, row);
            if (inside == 1 || inside == 0) continue;
            refused += texelMass(layout, width, height, col, row, pdf) * (1 / inside - 1);
        }
    return refused;
}

// --- Sampling: χ² ------------------------------------------------------------------------------

// Draws kSamples directions; *failed counts the draws sample() refused.
template <class Add>
void drawSamples(const EnvironmentMap& map, uint64_t seed, int* failed, const Add& add) {
    *failed = 0;
    for (int i = 0; i < kSamples; ++i) {
        LightSample ls;
        if (map.sample(Vec3(0.0f), uniform2(seed, i), 0, &ls))
            add(ls.direction);
        else
            ++*failed;
    }
}

// χ² with an extra cell for the refused draws, which expects whatever mass the others lack.
Chi2Outcome chi2WithRefusals(std::vector<double> observed, int failed,
                             std::vector<double> expected) {
    double total = 0;
    for (double e : expected)
        total += e;
    observed.push_back(failed);
    expected.push_back(std::max(0.0, kSamples - total));
    return chi2GoodnessOfFit(observed, expected);
}

// Sparse maps: samples binned by texel through the documented inverse map, against the mass
// each texel has under `pdf` (texelMass). Exact: no quadrature, however sharp the map, and the
// lat-long pole and probe rim, where the density is unbounded, are no harder than elsewhere.
// Independent of env_layout.cpp: directions to texels and the Jacobian are the test's own.
Chi2Outcome texelChi2(const EnvironmentMap& map, const SparseMap& m, uint64_t seed,
                      const std::function<double(const Vec3&)>& pdf) {
    std::vector<double> observed(size_t(m.width) * m.height, 0.0), expected(observed.size());
    int failed;
    drawSamples(map, seed, &failed, [&](const Vec3& w) {
        const Vec2 st = documentedImagePoint(m.layout, w);
        const int col = std::min(int(st.x * m.width), m.width - 1);
        const int row = std::min(int(st.y * m.height), m.height - 1);
        observed[size_t(row) * m.width + col] += 1;
    });
    for (int row = 0; row < m.height; ++row)
        for (int col = 0; col < m.width; ++col)
            expected[size_t(row) * m.width + col] =
                kSamples * texelMass(m.layout, m.width, m.height, col, row, pdf);
    if (std::string(m.layout) == "latlong") {
        EXPECT_EQ(failed, 0);
    }
    return chi2WithRefusals(observed, failed, expected);
}

class SparseMaps : public ::testing::TestWithParam<SparseMap> {
  protected:
    std::unique_ptr<EnvironmentMap> load() const {
        const SparseMap& m = GetParam();
        return loadMap(writeMap("sparse.exr", m.width, m.height, m.pixel), m.layout);
    }
};

TEST_P(SparseMaps, DirectionsFollowPdf) {
    const auto map = load();
    kChi2.expectFits(texelChi2(*map, GetParam(), 100,
                               [&](const Vec3& w) { return map->directionPdf(Vec3(0.0f), w); }),
                     std::string("sparse ") + GetParam().layout + " map");
}

// ∫ pdf dω over the sphere is 1 less the refused mass (only the probe's rim texel has some).
TEST_P(SparseMaps, PdfIntegratesToOne) {
    const SparseMap& m = GetParam();
    const auto map = load();
    const double integral =
        sphereIntegral([&](const Vec3& w) { return map->directionPdf(Vec3(0.0f), w); }, m.layout,
                       m.width, m.height, 16);
    const double refused = refusedMass(*map, m.layout, m.width, m.height);
    std::printf("sparse %s map: ∫ pdf dω = %.6f, refused mass %.6f\n", m.layout, integral, refused);
    EXPECT_NEAR(integral, 1 - refused, 1e-5);
    if (std::string(m.layout) == "probe") {
        EXPECT_GT(refused, 1e-4) << "the rim texel";
    }
}

// A sample carries the radiance and density of the texel it was drawn in; escaped rays and MIS
// look its direction up and find the same texel, save where rounding carries the direction
// across a texel's edge: at most 1 in 1000 samples (measured: at most 1 in 10⁴), and the
// density agrees to rounding (the layout's Jacobian at the point, and at the point found again
// from the direction). Returns how many crossed.
int expectSamplesAgreeWithLookups(const EnvironmentMap& map, const Vec3& reference, uint64_t seed,
                                  const std::string& what) {
    constexpr int kDraws = 10000;
    int drawn = 0, crossed = 0;
    for (int i = 0; i < kDraws; ++i) {
        LightSample ls;
        if (!map.sample(reference, uniform2(seed, uint64_t(i)), 0, &ls)) continue;
        ++drawn;
        EXPECT_FALSE(ls.isDelta);
        EXPECT_GT(length(ls.position - reference), 2.0f) << "beyond the scene's sphere";
        const float pdf = map.directionPdf(Vec3(0.0f), ls.direction);
        if (!(ls.radiance == map.escapedRadiance(ls.direction)) ||
            !(std::abs(pdf - ls.pdf) <= 1e-4f * ls.pdf))
            ++crossed;
    }
    std::printf("%s: %d of %d samples' directions looked up in another texel\n", what.c_str(),
                crossed, drawn);
    EXPECT_GT(drawn, kDraws / 2) << what;
    EXPECT_LE(crossed, drawn / 1000) << what;
    return crossed;
}

TEST_P(SparseMaps, SamplesAgreeWithEscapedRadianceAndDirectionPdf) {
    const SparseMap& m = GetParam();
    const auto map = load();
    expectSamplesAgreeWithLookups(*map, Vec3(1, 2, 3), 7, m.layout);
    // The radiance is the file's texel where the sample's direction is.
    for (int i = 0; i < 10000; ++i) {
        LightSample ls;
        if (!map->sample(Vec3(1, 2, 3), uniform2(7, i), 0, &ls)) continue;
        if (!(ls.radiance == map->escapedRadiance(ls.direction))) continue;  // crossed, above
        const Vec2 st = documentedImagePoint(m.layout, ls.direction);
        EXPECT_EQ(ls.radiance, m.pixel(int(st.x * m.width), int(st.y * m.height)));
    }
}

INSTANTIATE_TEST_SUITE_P(Layouts, SparseMaps, ::testing::ValuesIn(kSparseMaps),
                         [](const auto& p) { return std::string(p.param.layout); });

// Negative control: sparse lat-long samples judged with a density that forgets the Jacobian
// (p(s, t) taken per steradian, renormalised).
TEST(EnvironmentMapNegativeControl, SamplesRejectPdfWithoutJacobian) {
    const SparseMap& m = kSparseMaps[0];
    const auto map = loadMap(writeMap("sparse.exr", m.width, m.height, m.pixel), m.layout);
    const auto noJacobian = [&](const Vec3& w) {
        const Vec2 st = documentedImagePoint(m.layout, w);
        return map->directionPdf(Vec3(0.0f), w) * documentedJacobian(m.layout, st.x, st.y);
    };
    const double norm = sphereIntegral(noJacobian, m.layout, m.width, m.height, 16);
    kChi2.expectRejects(
        texelChi2(*map, m, 100, [&](const Vec3& w) { return noJacobian(w) / norm; }),
        "pdf without the Jacobian");
}

// Galileo: directions in a DirectionHistogram, against expected counts integrated in image
// space texel by texel: pdf(ω) dω = pdf(ω(s, t)) · J(s, t) ds dt. A texel whose four corners
// fall in one cell adds its whole mass there (pdf · J is constant over a texel); the others (on
// cell edges, or crossing the probe's rim) are split over a 12 × 12 sub-grid. Aligned with the
// texels, this stays accurate for a 10⁶-texel map where a direction-space midpoint rule would
// alias. `h` must be empty.
std::vector<double> expectedByTexels(const EnvironmentMap& map, const std::string& layout,
                                     int width, int height, DirectionHistogram h) {
    constexpr size_t kNone = std::numeric_limits<size_t>::max();
    std::vector<size_t> corner(size_t(width + 1) * (height + 1));
    for (int row = 0; row <= height; ++row)
        for (int col = 0; col <= width; ++col) {
            Vec3 w;
            const bool inside =
                documentedDirection(layout, double(col) / width, double(row) / height, &w);
            corner[size_t(row) * (width + 1) + col] = inside ? h.cellOf(w) : kNone;
        }
    const double texelArea = 1.0 / (double(width) * height);
    constexpr int kSub = 12;
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            const size_t c = corner[size_t(row) * (width + 1) + col];
            const bool whole = c != kNone && corner[size_t(row) * (width + 1) + col + 1] == c &&
                               corner[size_t(row + 1) * (width + 1) + col] == c &&
                               corner[size_t(row + 1) * (width + 1) + col + 1] == c;
            const int n = whole ? 1 : kSub;
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b) {
                    const double s = (col + (a + 0.5) / n) / width;
                    const double t = (row + (b + 0.5) / n) / height;
                    Vec3 w;
                    if (!documentedDirection(layout, s, t, &w)) continue;
                    h.add(w, map.directionPdf(Vec3(0.0f), w) * documentedJacobian(layout, s, t) *
                                 texelArea / (n * n) * kSamples);
                }
        }
    return h.counts();
}

TEST_P(GalileoProbe, DirectionsFollowPdf) {
    const auto map = loadMap(*file_, GetParam());
    DirectionHistogram h(24, 48);
    int failed;
    drawSamples(*map, 200, &failed, [&](const Vec3& w) { h.add(w); });
    const std::vector<double> expected =
        expectedByTexels(*map, GetParam(), 1000, 1000, DirectionHistogram(24, 48));
    kChi2.expectFits(chi2WithRefusals(h.counts(), failed, expected), "Galileo as " + GetParam());
    std::printf("Galileo as %s: %d of %d samples refused\n", GetParam().c_str(), failed, kSamples);
}

// ∫ pdf dω over the sphere (4 × 4 points per texel) is 1 less the refused mass.
TEST_P(GalileoProbe, PdfIntegratesToOne) {
    const auto map = loadMap(*file_, GetParam());
    const double integral = sphereIntegral(
        [&](const Vec3& w) { return map->directionPdf(Vec3(0.0f), w); }, GetParam(), 1000, 1000, 4);
    const double refused = refusedMass(*map, GetParam(), 1000, 1000);
    std::printf("Galileo as %s: ∫ pdf dω = %.7f, refused mass %.2e\n", GetParam().c_str(), integral,
                refused);
    EXPECT_NEAR(integral, 1 - refused, 1e-5);
}

// escapedRadiance is the file's texel (nearest lookup), masked outside the disc; sample()
// agrees with escapedRadiance and directionPdf; the radiance integral (and so the power) is the
// file's, over the texels the layout keeps.
TEST_P(GalileoProbe, LookupsAreTheFilesTexels) {
    const RgbImage image = readRgbImage(*file_);
    ASSERT_EQ(image.width, 1000);
    const auto map = loadMap(Json{{"type", "environment"},
                                  {"file", file_->string()},
                                  {"layout", GetParam()},
                                  {"scale", {2, 1, 0.5}}});
    const Rgb scale(2, 1, 0.5f);
    double integral[3] = {0, 0, 0}, outsideLuminance = 0;
    for (int row = 0; row < 1000; ++row)
        for (int col = 0; col < 1000; ++col) {
            const Vec2 centre((col + 0.5f) / 1000, (row + 0.5f) / 1000);
            const float jacobian = map->layout().jacobian(centre);
            const Rgb file = image.pixels[size_t(row) * 1000 + col];
            if (jacobian == 0) {
                outsideLuminance += file.luminance();
                continue;
            }
            // The map's own 4 × 4 rule for a texel's solid angle (the sparse probe checks it).
            const double solidAngle = texelJacobian(GetParam(), 1000, 1000, col, row, 4) / 1e6;
            for (int c = 0; c < 3; ++c)
                integral[c] += double(file[c]) * scale[c] * solidAngle;
            if ((row * 1000 + col) % 97 != 0) continue;
            Vec3 w;
            float j;
            ASSERT_TRUE(map->layout().direction(centre, &w, &j));
            EXPECT_EQ(map->escapedRadiance(w), file * scale) << col << ", " << row;
        }
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(map->radianceIntegral()[c], integral[c], 1e-4 * integral[c]);
    EXPECT_NEAR(map->power().g, M_PI * integral[1], 1e-4 * M_PI * integral[1]) << "r = 1";
    if (GetParam() == "probe") {
        EXPECT_GT(outsideLuminance, 100) << "the copyright notice the probe's mask removes";
    }
    expectSamplesAgreeWithLookups(*map, Vec3(0.0f), 8, "Galileo, " + GetParam());
}

// sampleStandIn, RIS's stand-in (blocks of 10 × 10 texels on this map): its pdf is the density of
// its directions, so E[L/pdf] = ∫ L dω over the map, both with the exact radiance (what RIS's f
// uses) and with the stand-in's own (ĝ's: a block's solid-angle mean carries the block's
// integral). z-tests of the means of 2²⁰ samples (luminance); Šidák over 2 layouts × 2 means.
// The negative control: a density 1.5 % too high is rejected.
struct ProxyMean {
    double mean = 0, standardError = 0;
};

ProxyMean proxyMean(const EnvironmentMap& map, const std::function<double(const LightSample&)>& f) {
    constexpr int kDraws = 1 << 20;
    double sum = 0, sumSquares = 0;
    for (int i = 0; i < kDraws; ++i) {
        LightSample ls;
        if (!map.sampleStandIn(Vec3(0.0f), uniform2(31, uint64_t(i)), 0, &ls)) continue;
        const double x = f(ls);
        sum += x;
        sumSquares += x * x;
    }
    const double mean = sum / kDraws;
    return {mean, std::sqrt(std::max(0.0, sumSquares / kDraws - mean * mean) / kDraws)};
}

double zOf(const ProxyMean& m, double expected) {
    return std::abs(m.mean - expected) / m.standardError;
}

TEST_P(GalileoProbe, ProxySamplesFollowTheirPdf) {
    const auto map = loadMap(*file_, GetParam());
    ASSERT_EQ(map->proxyBlock(), 10);
    const double integral = map->radianceIntegral().luminance();
    const double threshold = zThreshold(sidakAlpha(0.01, 4));
    const ProxyMean exact = proxyMean(
        *map, [&](const LightSample& s) { return map->exactRadiance(s).luminance() / s.pdf; });
    const ProxyMean own =
        proxyMean(*map, [](const LightSample& s) { return s.radiance.luminance() / s.pdf; });
    std::printf(
        "Galileo as %s: ∫L dω %.5f, E[L/pdf] %.5f ± %.5f (exact L), %.5f ± %.5f (block L)\n",
        GetParam().c_str(), integral, exact.mean, exact.standardError, own.mean, own.standardError);
    EXPECT_LT(zOf(exact, integral), threshold);
    EXPECT_LT(zOf(own, integral), threshold);
    const ProxyMean wrong = proxyMean(*map, [&](const LightSample& s) {
        return map->exactRadiance(s).luminance() / (1.015 * s.pdf);
    });
    EXPECT_GT(zOf(wrong, integral), threshold) << "the negative control";
}

INSTANTIATE_TEST_SUITE_P(Layouts, GalileoProbe, ::testing::Values("probe", "latlong"),
                         [](const auto& p) { return p.param; });

// --- Masking, rotation, errors ------------------------------------------------------------------

// The probe's masked texels give no light and are never sampled: the corner texel (no direction
// reaches it) and the rim texel whose centre is outside the disc, seen through its corner that
// is inside.
TEST(EnvironmentMaps, ProbeMaskRemovesTexelsOutsideTheDisc) {
    const auto map = loadMap(writeMap("sparse.exr", kProbeSize, kProbeSize, sparseProbe), "probe");
    // Texel (0, 4) spans u ∈ [−1, −0.875], v ∈ [0.375, 0.5]; its corner (−0.875, 0.375) is at
    // ρ = 0.952: a point just inside that corner is in the disc and in the texel.
    const float u = -0.876f, v = 0.376f;
    Vec3 w;
    float jacobian;
    ASSERT_TRUE(map->layout().direction(Vec2((u + 1) / 2, (1 - v) / 2), &w, &jacobian));
    const Vec2 back = map->layout().imagePoint(w);
    ASSERT_EQ(int(back.x * kProbeSize), 0);
    ASSERT_EQ(int(back.y * kProbeSize), 4);
    EXPECT_EQ(map->escapedRadiance(w), Rgb(0.0f));
    EXPECT_EQ(map->directionPdf(Vec3(0.0f), w), 0.0f);
    // Only texels whose centre is in the disc carry power, not the masked ones (100 and 50),
    // each with its solid angle (here to 64 × 64 points; the map's 4 × 4 rule is within 1e-3).
    double expected = 0;
    for (int row = 0; row < kProbeSize; ++row)
        for (int col = 0; col < kProbeSize; ++col)
            if (documentedJacobian("probe", (col + 0.5) / kProbeSize, (row + 0.5) / kProbeSize) > 0)
                expected += sparseProbe(col, row).g *
                            texelJacobian("probe", kProbeSize, kProbeSize, col, row, 64) /
                            (kProbeSize * kProbeSize);
    EXPECT_NEAR(map->radianceIntegral().g, expected, 1e-3 * expected);
}

// A single bright texel, rotated: its light comes from R·d, where d is its direction by the
// documented lat-long formula, and every sample lies within the texel's extent around R·d.
TEST(EnvironmentMaps, RotationMovesTheBrightTexel) {
    constexpr int kCol = 5, kRow = 2;
    const fs::path file = writeMap("one.exr", 16, 8, [](int col, int row) {
        return col == kCol && row == kRow ? Rgb(7) : Rgb(0.0f);
    });
    Vec3 d;
    documentedDirection("latlong", (kCol + 0.5) / 16, (kRow + 0.5) / 8, &d);
    struct Case {
        Json rotate;
        Vec3 expected;
    };
    // Right-handed rotations by 90°: about +Y (x, y, z) → (z, y, −x); about +X → (x, −z, y);
    // the two in turn.
    const Case cases[] = {
        {Json{{"axis", {0, 1, 0}}, {"angle", 90}}, Vec3(d.z, d.y, -d.x)},
        {Json{{"axis", {1, 0, 0}}, {"angle", 90}}, Vec3(d.x, -d.z, d.y)},
        {Json::array(
             {Json{{"axis", {0, 1, 0}}, {"angle", 90}}, Json{{"axis", {1, 0, 0}}, {"angle", 90}}}),
         Vec3(d.z, d.x, d.y)},
    };
    for (const Case& c : cases) {
        const auto map = loadMap(Json{{"type", "environment"},
                                      {"file", file.string()},
                                      {"layout", "latlong"},
                                      {"transform", {{"rotate", c.rotate}}}});
        EXPECT_EQ(map->escapedRadiance(c.expected), Rgb(7)) << c.rotate;
        EXPECT_EQ(map->escapedRadiance(d), Rgb(0.0f)) << c.rotate;
        // The texel spans 22.5° × 22.5°: every sample is within its half-diagonal of R·d.
        const float cosMax = std::cos(float(M_PI) / 16 * 1.5f);
        int sampled = 0;
        for (int i = 0; i < 1000; ++i) {
            LightSample ls;
            if (!map->sample(Vec3(0.0f), uniform2(9, i), 0, &ls)) continue;
            ++sampled;
            EXPECT_GT(dot(ls.direction, c.expected), cosMax) << c.rotate;
        }
        EXPECT_GT(sampled, 990);
    }
}

TEST(EnvironmentMaps, MissingFileNamesTheFileAndTheSearchPath) {
    const Json j{{"type", "environment"}, {"file", "envmaps/nothing.hdr"}, {"layout", "probe"}};
    ObjectReader reader(j, "/lights/0");
    try {
        makeLight(reader, AssetResolver({"/nonexistent/dir"}), Transform());
        FAIL() << "no error";
    } catch (const ConfigError& e) {
        const std::string m = e.what();
        EXPECT_EQ(e.pointer(), "/lights/0/file");
        EXPECT_NE(m.find("envmaps/nothing.hdr"), std::string::npos) << m;
        EXPECT_NE(m.find("/nonexistent/dir"), std::string::npos) << m;
    }
}

TEST(EnvironmentMaps, ProbeMustBeSquare) {
    const fs::path file = writeMap("wide.exr", 8, 4, [](int, int) { return Rgb(1); });
    const Json j{{"type", "environment"}, {"file", file.string()}, {"layout", "probe"}};
    ObjectReader reader(j, "/lights/0");
    try {
        makeLight(reader, AssetResolver({}), Transform());
        FAIL() << "no error";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/lights/0/layout") << e.what();
    }
}

// --- Renders: a constant map is a constant environment ------------------------------------------

// A convex diffuse sphere under a map of constant radiance L reflects albedo·L (as under the
// "radiance" environment in test_analytic_scenes). For the probe, the masked rim texels leave a
// small cap around −Z dark; the camera on +Z sees only sphere points with n·z > 1/3, which
// have that cap below their horizon.
class ConstantMapRenders : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(ConstantMapRenders, DiffuseSphereRendersAlbedoTimesL) {
    const auto [layout, integrator] = GetParam();
    const int height = layout == "probe" ? 64 : 32;
    const fs::path file =
        writeMap("constant.exr", 64, height, [](int, int) { return Rgb(1.5f, 1, 0.5f); });
    const LoadedScene scene = loadSceneText(
        R"({"render": {"resolution": [16, 16], "spp": 64, "max_depth": -1, "rr_depth": 1},
            "integrator": {"type": ")" +
        integrator + R"("},
            "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 20},
            "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                        "material": {"type": "lambert", "albedo": [0.6, 0.3, 0.9]}}],
            "lights": [{"type": "environment", "file": ")" +
        file.string() + R"(", "layout": ")" + layout + R"("}]})");
    const TestRender r = renderScene(scene, 64);
    const Rgb expected(0.9f, 0.3f, 0.45f);
    for (int c = 0; c < 3; ++c) {
        const Estimate e = imageMean(r.film, c);
        EXPECT_LE(std::abs(e.mean - expected[c]), kZ * e.standardError + 1e-5 * expected[c])
            << "channel " << c << ": " << e.mean << " ± " << e.standardError;
    }
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx) {
            const Estimate e = regionMean(r.film, 0, 4 * bx, 4 * by, 4 * bx + 4, 4 * by + 4);
            EXPECT_LE(std::abs(e.mean - expected[0]), kZ * e.standardError + 1e-5 * expected[0])
                << "block " << bx << ", " << by << ": " << e.mean << " ± " << e.standardError;
        }
}

INSTANTIATE_TEST_SUITE_P(LayoutsAndIntegrators, ConstantMapRenders,
                         ::testing::Combine(::testing::Values("latlong", "probe"),
                                            ::testing::Values("path_mis", "direct")),
                         [](const auto& p) {
                             return std::get<0>(p.param) + "_" + std::get<1>(p.param);
                         });

// --- MIS: the direct-lighting strategies agree ---------------------------------------------------

// Light sampling (sample()), BSDF sampling (escaped rays weighted by directionPdf(), polygon
// hits by the polygon's solid-angle pdf) and their MIS combination estimate the same image of a
// diffuse sphere on a polygon floor under a sparse map and a polygonal light: they agree within
// Šidák-corrected z-tests (2 maps × 3 pairs × 3 channels). The camera looks down and sees only
// the floor and the sphere, not the lights themselves, which every strategy would count alike.
TEST(EnvironmentMapMis, DirectStrategiesAgree) {
    const double z = zThreshold(sidakAlpha(0.01, 18));
    for (const SparseMap& m : kSparseMaps) {
        const fs::path file = writeMap("sparse.exr", m.width, m.height, m.pixel);
        std::vector<TestRender> renders;
        uint32_t seed = 40;
        for (const char* strategy : {"light", "bsdf", "mis"}) {
            const LoadedScene scene = loadSceneText(
                R"({"render": {"resolution": [24, 24]},
                    "integrator": {"type": "direct", "strategy": ")" +
                std::string(strategy) + R"("},
                    "camera": {"position": [0, 3, 1], "look_at": [0, -0.7, 0], "fov": 35},
                    "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 0.7,
                                "material": {"type": "lambert", "albedo": 0.7}},
                               {"type": "polygon", "vertices": [[-2, -0.7, 1.5], [1.5, -0.7, 2],
                                 [2, -0.7, -1], [0, -0.7, -2.5], [-2, -0.7, -1]],
                                "material": {"type": "lambert", "albedo": 0.5}},
                               {"type": "polygon", "vertices": [[1, 1.75, -0.5], [2.1, 1.86, -0.4],
                                 [2, 1.85, 0.6], [0.9, 1.74, 0.5]],
                                "emission": {"radiance": [6, 4, 2]}}],
                    "lights": [{"type": "environment", "file": ")" +
                file.string() + R"(", "layout": ")" + m.layout + R"("}]})");
            renders.push_back(renderScene(scene, 256, seed++));
        }
        expectImageMeansAgreePairwise(renders, {"light", "bsdf", "mis"}, z, m.layout);
    }
}

}  // namespace
}  // namespace rr::test
