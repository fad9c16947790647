// Scenes whose pixel values are known in closed form (or by deterministic quadrature),
// rendered by each integrator and compared with z-tests against the per-pixel variance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <tuple>

#include "scene/scene_features.h"
#include "support/chi2.h"
#include "support/scene_testing.h"

namespace rr::test {
namespace {

// Family-wise level 0.01 over every z-test in this file (Šidák): 5 furnace/sphere scenes × 2
// integrators × (3 channels + 16 blocks) + 2 motion scenes × 2 integrators × 17 + the lights
// over a floor (3 scales × 2 integrators + 2 integrators) × 17 = 394.
constexpr int kComparisons = 394;
const double kZ = zThreshold(sidakAlpha(0.01, kComparisons));

// Checks the image mean and the mean of each of 4×4 blocks against `expected` (per channel
// for the image mean, luminance-free: channel 0 for blocks).
void expectRegionsMatch(const Film& film, const Rgb& expected, const std::string& what) {
    for (int c = 0; c < 3; ++c) {
        const Estimate e = imageMean(film, c);
        EXPECT_LE(std::abs(e.mean - expected[c]), kZ * e.standardError + 1e-5 * expected[c])
            << what << " channel " << c << ": mean " << e.mean << " ± " << e.standardError
            << ", expected " << expected[c];
    }
    const int bw = film.width() / 4, bh = film.height() / 4;
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx) {
            const Estimate e = regionMean(film, 0, bx * bw, by * bh, (bx + 1) * bw, (by + 1) * bh);
            EXPECT_LE(std::abs(e.mean - expected[0]), kZ * e.standardError + 1e-5 * expected[0])
                << what << " block (" << bx << ", " << by << "): " << e.mean << " ± "
                << e.standardError << ", expected " << expected[0];
        }
}

class AnalyticScenes : public ::testing::TestWithParam<std::string> {
  protected:
    std::string integrator() const { return GetParam(); }
    std::string header(int spp) const {
        return R"({"render": {"resolution": [16, 16], "spp": )" + std::to_string(spp) +
               R"(, "max_depth": -1, "rr_depth": 1},
                  "integrator": {"type": ")" +
               integrator() + R"("},)";
    }
};

// A closed diffuse enclosure of albedo ρ emitting Le everywhere: L = Le + ρL ⇒ Le / (1 − ρ).
TEST_P(AnalyticScenes, FurnaceSphereRendersLeOverOneMinusAlbedo) {
    const LoadedScene scene = loadSceneText(header(256) + R"(
        "camera": {"position": [0.2, -0.1, 0.3], "look_at": [0, 0, -1], "fov": 100},
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                    "material": {"type": "lambert", "albedo": [0.5, 0.25, 0.75]},
                    "emission": {"radiance": [1, 2, 0.5], "two_sided": true}}]})");
    const TestRender r = renderScene(scene, 256);
    expectRegionsMatch(r.film, Rgb(1 / 0.5f, 2 / 0.75f, 0.5f / 0.25f), "furnace sphere");
}

TEST_P(AnalyticScenes, FurnaceBoxOfQuadsRendersLeOverOneMinusAlbedo) {
    std::string walls;
    const char* faces[6] = {R"("corner": [-1, -1, -1], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0])",
                            R"("corner": [-1, -1, 1], "edge_u": [0, 2, 0], "edge_v": [2, 0, 0])",
                            R"("corner": [-1, -1, -1], "edge_u": [0, 2, 0], "edge_v": [0, 0, 2])",
                            R"("corner": [1, -1, -1], "edge_u": [0, 0, 2], "edge_v": [0, 2, 0])",
                            R"("corner": [-1, -1, -1], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0])",
                            R"("corner": [-1, 1, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2])"};
    for (int i = 0; i < 6; ++i)
        walls += std::string(i ? "," : "") + R"({"type": "quad", )" + faces[i] +
                 R"(, "material": "wall", "emission": {"radiance": 0.5, "two_sided": true}})";
    const LoadedScene scene = loadSceneText(header(256) + R"(
        "camera": {"position": [0.1, 0.2, 0.5], "look_at": [-1, -0.3, -1], "fov": 90},
        "materials": {"wall": {"type": "lambert", "albedo": 0.6}},
        "shapes": [)" + walls + "]}");
    const TestRender r = renderScene(scene, 256);
    expectRegionsMatch(r.film, Rgb(0.5f / 0.4f), "furnace box");
}

// A convex diffuse sphere inside a uniform emitter L: no self-illumination, so Lo = ρL.
// The camera sees only the sphere (its angular radius 19.5° exceeds the 14.1° corner angle).
TEST_P(AnalyticScenes, ConvexDiffuseSphereUnderUniformEmitterRendersAlbedoTimesL) {
    const LoadedScene scene = loadSceneText(header(64) + R"(
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 20},
        "shapes": [
          {"type": "sphere", "center": [0, 0, 0], "radius": 10,
           "emission": {"radiance": [1.5, 1, 0.5], "two_sided": true}},
          {"type": "sphere", "center": [0, 0, 0], "radius": 1,
           "material": {"type": "lambert", "albedo": [0.6, 0.3, 0.9]}}]})");
    const TestRender r = renderScene(scene, 64);
    expectRegionsMatch(r.film, Rgb(0.9f, 0.3f, 0.45f), "sphere in uniform emitter");
}

// The same sphere under a constant environment light (an infinite light, reached by escaping
// rays and by next-event estimation towards uniformly sampled directions): Lo = ρL.
TEST_P(AnalyticScenes, ConvexDiffuseSphereUnderConstantEnvironmentRendersAlbedoTimesL) {
    const LoadedScene scene = loadSceneText(header(64) + R"(
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 20},
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                    "material": {"type": "lambert", "albedo": [0.6, 0.3, 0.9]}}],
        "lights": [{"type": "environment", "radiance": [1.5, 1, 0.5]}]})");
    const TestRender r = renderScene(scene, 64);
    expectRegionsMatch(r.film, Rgb(0.9f, 0.3f, 0.45f), "sphere under a constant environment");
}

// An emitter seen directly renders its radiance exactly, in every pixel.
TEST_P(AnalyticScenes, EmissiveQuadSeenDirectlyRendersItsExactRadiance) {
    for (const char* camera :
         {R"("type": "pinhole")",
          R"("type": "thin_lens", "aperture_radius": 0.2, "focus_distance": 1)"}) {
        const LoadedScene scene = loadSceneText(header(4) + R"(
            "camera": {)" + camera + R"(, "position": [0, 0, 1], "look_at": [0, 0, 0], "fov": 60},
            "shapes": [{"type": "quad", "corner": [-5, -5, 0], "edge_u": [10, 0, 0],
                        "edge_v": [0, 10, 0], "emission": {"radiance": [2, 3, 4]}}]})");
        const TestRender r = renderScene(scene, 4);
        for (int y = 0; y < r.film.height(); ++y)
            for (int x = 0; x < r.film.width(); ++x) {
                ASSERT_EQ(r.film.mean(x, y), Rgb(2, 3, 4)) << camera << " pixel " << x << "," << y;
                ASSERT_EQ(r.film.varianceOfMean(x, y), Rgb(0.0f));
            }
    }
}

// Motion blur: an emitter translating over the shutter. The expected pixel value is L times
// the fraction of (film position, time) whose ray meets the moving shape, computed by
// deterministic quadrature with an analytic hit test independent of Embree.
// The hit test receives the scene time computed here from the shutter settings, not the
// camera's, so the camera's shutter mapping is under test too.
using MovingHitTest = std::function<bool(const Ray&, float time)>;

double coveredFraction(const Scene& scene, int px, int py, const MovingHitTest& hits) {
    constexpr int kFilm = 12, kTime = 48;
    const Camera& camera = scene.camera();
    const float open = camera.settings().shutterOpen, close = camera.settings().shutterClose;
    int covered = 0;
    for (int a = 0; a < kFilm; ++a)
        for (int b = 0; b < kFilm; ++b)
            for (int t = 0; t < kTime; ++t) {
                const Vec2 film(px + (a + 0.5f) / kFilm, py + (b + 0.5f) / kFilm);
                const float u = (t + 0.5f) / kTime;
                const Ray ray = inFileSpace(scene, camera.generateRay(film, Vec2(0.5f, 0.5f), u));
                covered += hits(ray, open + u * (close - open));
            }
    return double(covered) / (kFilm * kFilm * kTime);
}

void expectMotionBlurMatchesQuadrature(const LoadedScene& scene, double radiance,
                                       const MovingHitTest& hits) {
    const TestRender r = renderScene(scene, 256);
    ASSERT_TRUE(sceneFeatures(*scene.scene).motionBlur);
    double expectedTotal = 0;
    Film expected(r.film.width(), r.film.height());
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x) {
            const double f = radiance * coveredFraction(*scene.scene, x, y, hits);
            expected.add(x, y, Rgb(float(f)));
            expectedTotal += f;
        }
    const Estimate e = imageMean(r.film, 0);
    const double mean = expectedTotal / (r.film.width() * r.film.height());
    // Quadrature error: the shape's edge sweeps cells of the 12×12×48 grid; its effect on the
    // image mean is below 1e-3 relative, far under the Monte Carlo error tested here.
    EXPECT_LE(std::abs(e.mean - mean), kZ * e.standardError + 1e-3 * mean)
        << "image mean " << e.mean << " ± " << e.standardError << ", quadrature " << mean;
    const int bw = r.film.width() / 4, bh = r.film.height() / 4;
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx) {
            const Estimate got =
                regionMean(r.film, 0, bx * bw, by * bh, (bx + 1) * bw, (by + 1) * bh);
            const Estimate want =
                regionMean(expected, 0, bx * bw, by * bh, (bx + 1) * bw, (by + 1) * bh);
            EXPECT_LE(std::abs(got.mean - want.mean), kZ * got.standardError + 1e-3 * radiance)
                << "block (" << bx << ", " << by << "): " << got.mean << " ± " << got.standardError
                << ", quadrature " << want.mean;
        }
}

TEST_P(AnalyticScenes, MovingQuadEmitterMatchesQuadrature) {
    const LoadedScene scene = loadSceneText(header(256) + R"(
        "camera": {"position": [0, 0, 2], "look_at": [0, 0, 0], "fov": 60, "shutter": [0.2, 0.9]},
        "shapes": [{"type": "quad", "corner": [-1, -0.4, 0], "edge_u": [0.8, 0, 0],
                    "edge_v": [0, 0.8, 0], "emission": {"radiance": 3},
                    "motion": {"translate": [1.5, 0.3, 0]}}]})");
    expectMotionBlurMatchesQuadrature(scene, 3.0, [](const Ray& ray, float time) {
        const float t = -ray.origin.z / ray.direction.z;
        const Vec3 p = ray.origin + ray.direction * t - Vec3(1.5f, 0.3f, 0) * time;
        return p.x >= -1 && p.x <= -0.2f && p.y >= -0.4f && p.y <= 0.4f;
    });
}

TEST_P(AnalyticScenes, MovingSphereEmitterMatchesQuadrature) {
    const LoadedScene scene = loadSceneText(header(256) + R"(
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 50, "shutter": [0, 1]},
        "shapes": [{"type": "sphere", "center": [-0.6, 0.1, 0], "radius": 0.35,
                    "emission": {"radiance": 2, "two_sided": true},
                    "motion": {"translate": [1.2, -0.2, 0.3]}}]})");
    expectMotionBlurMatchesQuadrature(scene, 2.0, [](const Ray& ray, float time) {
        const Vec3 c = Vec3(-0.6f, 0.1f, 0) + Vec3(1.2f, -0.2f, 0.3f) * time;
        const Vec3 o = ray.origin - c;
        const float b = dot(o, ray.direction), cc = dot(o, o) - 0.35f * 0.35f;
        return b * b - cc >= 0;
    });
}

// A glass sphere (no absorption) inside a uniform emitter: radiance is conserved along every
// path (the 1/η² on entering is undone on leaving), so every pixel is exactly L and — with
// Russian roulette compensating for η² — every sample is, too: zero variance.
TEST_P(AnalyticScenes, GlassSphereInUniformEmitterConservesRadianceWithZeroVariance) {
    const LoadedScene scene = loadSceneText(header(64) + R"(
        "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 20},
        "shapes": [
          {"type": "sphere", "radius": 10, "emission": {"radiance": 1.5, "two_sided": true}},
          {"type": "sphere", "radius": 1, "material": {"type": "dielectric", "ior": 1.5}}]})");
    const TestRender r = renderScene(scene, 64);
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x) {
            ASSERT_NEAR(r.film.mean(x, y).g, 1.5f, 1.5e-5f) << x << "," << y;
            ASSERT_LT(r.film.varianceOfMean(x, y).g, 1e-10f) << x << "," << y;
        }
}

// Expected pixel values by quadrature over the pixel footprint, for a camera looking at the
// floor y = 0 (every pixel must see it): `radiance(p)` is the closed-form value at floor point p.
Film floorQuadrature(const Scene& scene, const std::function<double(const Vec3&)>& radiance) {
    constexpr int kSub = 12;
    const Camera& camera = scene.camera();
    Film expected(camera.width(), camera.height());
    for (int y = 0; y < camera.height(); ++y)
        for (int x = 0; x < camera.width(); ++x) {
            double sum = 0;
            for (int a = 0; a < kSub; ++a)
                for (int b = 0; b < kSub; ++b) {
                    const Ray ray = inFileSpace(
                        scene,
                        camera.generateRay(Vec2(x + (a + 0.5f) / kSub, y + (b + 0.5f) / kSub),
                                           Vec2(0.5f, 0.5f), 0));
                    const double t = -double(ray.origin.y) / ray.direction.y;
                    sum += radiance(ray.origin + ray.direction * float(t));
                }
            expected.add(x, y, Rgb(float(sum / (kSub * kSub))));
        }
    return expected;
}

void expectMatchesQuadrature(const Film& film, const Film& expected, const std::string& what) {
    const Estimate e = imageMean(film, 0), want = imageMean(expected, 0);
    EXPECT_LE(std::abs(e.mean - want.mean), kZ * e.standardError + 1e-3 * want.mean)
        << what << ": image mean " << e.mean << " ± " << e.standardError << ", expected "
        << want.mean;
    const int bw = film.width() / 4, bh = film.height() / 4;
    for (int by = 0; by < 4; ++by)
        for (int bx = 0; bx < 4; ++bx) {
            const Estimate got =
                regionMean(film, 0, bx * bw, by * bh, (bx + 1) * bw, (by + 1) * bh);
            const Estimate w =
                regionMean(expected, 0, bx * bw, by * bh, (bx + 1) * bw, (by + 1) * bh);
            EXPECT_LE(std::abs(got.mean - w.mean), kZ * got.standardError + 1e-3 * w.mean)
                << what << " block (" << bx << ", " << by << "): " << got.mean << " ± "
                << got.standardError << ", expected " << w.mean;
        }
}

// Form factor from a floor point to an axis-aligned rectangle [x0,x1]×[z0,z1] at height h
// facing down: the sum over the four corner sub-rectangles of the point-to-corner formula
// F = 1/(2π) [X/√(1+X²) atan(Y/√(1+X²)) + Y/√(1+Y²) atan(X/√(1+Y²))], X = w/h, Y = l/h,
// with signs for corners on the same side (Howell's catalogue of configuration factors).
double rectangleFormFactor(double px, double pz, double x0, double x1, double z0, double z1,
                           double h) {
    auto corner = [h](double w, double l) {
        const double X = std::abs(w) / h, Y = std::abs(l) / h;
        const double f = (X / std::sqrt(1 + X * X) * std::atan(Y / std::sqrt(1 + X * X)) +
                          Y / std::sqrt(1 + Y * Y) * std::atan(X / std::sqrt(1 + Y * Y))) /
                         (2 * M_PI);
        return (w < 0) == (l < 0) ? f : -f;
    };
    return corner(x1 - px, z1 - pz) - corner(x0 - px, z1 - pz) - corner(x1 - px, z0 - pz) +
           corner(x0 - px, z0 - pz);
}

// Scenes of a diffuse floor (y = 0) under square quads, built as JSON objects.
Json square(double halfSize, double y, bool facingUp) {
    const double z = facingUp ? halfSize : -halfSize;  // edge_u × edge_v = ±y
    return {{"type", "quad"},
            {"corner", {-halfSize, y, z}},
            {"edge_u", {2 * halfSize, 0, 0}},
            {"edge_v", {0, 0, -2 * z}}};
}

Json floorScene(const std::string& integrator, double floorHalfSize, double albedo,
                const Json& camera) {
    Json floor = square(floorHalfSize, 0, /*facingUp=*/true);
    floor["material"] = {{"type", "lambert"}, {"albedo", albedo}};
    return {{"render", {{"resolution", {16, 16}}, {"max_depth", 1}}},
            {"integrator", {{"type", integrator}}},
            {"camera", camera},
            {"shapes", {floor}}};
}

// A camera at `height` looking obliquely down at the floor towards x = `lookX` (the 30° view
// sees floor only).
Json obliqueCamera(double height, double lookX) {
    return {{"position", {0, height, 0}}, {"look_at", {lookX, 0, 0}}, {"fov", 30}};
}

// A square light close over a diffuse floor (height 1/20 of its size, so shadow rays are short
// and end on a surface a hair away), at scene scales from 0.1 mm to km: the result is the
// closed-form form factor, whatever the unit. The camera, under the light, looks obliquely
// down at the floor only, from below the light's centre out past its edge.
class LightOverFloor : public ::testing::TestWithParam<std::tuple<std::string, double>> {};

TEST_P(LightOverFloor, SquareLightCloseOverAFloorMatchesTheFormFactor) {
    const auto [integrator, scale] = GetParam();
    const double a = 1.0 * scale, h = 0.1 * scale, albedo = 0.5, radiance = 2.0;
    Json doc = floorScene(integrator, 4 * a, albedo, obliqueCamera(0.09 * scale, 0.3 * scale));
    Json light = square(a, h, /*facingUp=*/false);
    light["emission"] = {{"radiance", radiance}};
    doc["shapes"].push_back(light);
    const LoadedScene scene = loadSceneJson(doc);
    const TestRender r = renderScene(scene, 256);
    const Film expected = floorQuadrature(*scene.scene, [&](const Vec3& p) {
        return albedo * radiance * rectangleFormFactor(p.x, p.z, -a, a, -a, a, h);
    });
    expectMatchesQuadrature(r.film, expected, integrator + " at scale " + std::to_string(scale));
}

// A distant light (1000 units up, 100 wide) with a black plate twice its width 0.05 under it:
// the gap is 5e-5 of the shadow rays' length. Every shadow ray must meet the plate — at every
// scene scale — so the floor is exactly black. (Shadow rays that stop a fixed fraction short
// of the light, e.g. 1e-4 of their length, miss the plate and leak light.)
TEST_P(LightOverFloor, OccluderJustUnderADistantLightBlocksEveryShadowRay) {
    const auto [integrator, scale] = GetParam();
    const double a = 50 * scale, height = 1000 * scale, gap = 0.05 * scale;
    Json doc = floorScene(integrator, 200 * scale, 0.5, obliqueCamera(2 * scale, 6 * scale));
    Json light = square(a, height, /*facingUp=*/false);
    light["emission"] = {{"radiance", 2}};
    Json plate = square(2 * a, height - gap, /*facingUp=*/false);
    plate["material"] = {{"type", "lambert"}, {"albedo", 0}};
    doc["shapes"].push_back(light);
    doc["shapes"].push_back(plate);
    const TestRender r = renderScene(loadSceneJson(doc), 64);
    for (int y = 0; y < r.film.height(); ++y)
        for (int x = 0; x < r.film.width(); ++x)
            ASSERT_EQ(r.film.mean(x, y), Rgb(0.0f)) << x << "," << y;
}

INSTANTIATE_TEST_SUITE_P(
    Scales, LightOverFloor,
    ::testing::Combine(::testing::Values("path_mis", "direct"), ::testing::Values(1e-4, 1.0, 1e3)),
    [](const auto& param) {
        const double scale = std::get<1>(param.param);
        return std::get<0>(param.param) + (scale < 1 ? "_tenth_mm" : scale > 1 ? "_km" : "_m");
    });

// A point light of intensity I at height h over a diffuse floor: L = ρ/π · I cos θ / d².
// (`path` cannot find point lights: they are only reachable by next-event estimation.)
TEST(PointLightOverFloor, MatchesTheInverseSquareLaw) {
    for (const std::string integrator : {"path_mis", "direct"}) {
        const LoadedScene scene = loadSceneText(
            R"({"render": {"resolution": [16, 16], "max_depth": 1},
                "integrator": {"type": ")" +
            integrator + R"("},
                "camera": {"position": [0, 1, 2], "look_at": [0, 0, 0], "fov": 50},
                "shapes": [{"type": "quad", "corner": [-10, 0, 10], "edge_u": [20, 0, 0],
                            "edge_v": [0, 0, -20], "material": {"type": "lambert", "albedo": 0.6}}],
                "lights": [{"type": "point", "position": [0.3, 0.8, -0.2], "intensity": 5}]})");
        const TestRender r = renderScene(scene, 16);
        const Film expected = floorQuadrature(*scene.scene, [](const Vec3& p) {
            const Vec3 d = Vec3(0.3f, 0.8f, -0.2f) - p;
            return 0.6 / M_PI * 5.0 * (d.y / length(d)) / lengthSquared(d);
        });
        expectMatchesQuadrature(r.film, expected, integrator);
    }
}

INSTANTIATE_TEST_SUITE_P(Integrators, AnalyticScenes, ::testing::Values("path", "path_mis"),
                         [](const auto& param) { return param.param; });

}  // namespace
}  // namespace rr::test
