// End-to-end tests of light sampling: directions drawn by light->sample() are histogrammed and
// compared (χ²) with the density that light->pdf() reports for the surface point a ray in each
// direction actually hits (scene.intersect), so sample() and pdf() are checked against each
// other and against the geometry. Also: radiance, pdf at the sampled point, point lights,
// power, and light selection.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "math/frame.h"
#include "sampling/hash.h"
#include "scene/lights/area_light.h"
#include "scene/lights/spot_light.h"
#include "scene/shape.h"
#include "scene/shapes/polygon.h"
#include "scene/shapes/triangle_mesh.h"
#include "support/chi2.h"
#include "support/histograms.h"
#include "support/scene_testing.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

// Every χ² run in this file: sphere from outside at 3 distances, from inside, quad, disk,
// two-sided disk from behind, triangle-mesh roof, polygon from two points and sampled by area
// (11 light-sampling runs), polygon area samples on its plane (1), uniform and power selection
// (2), and 5 negative controls.
constexpr int kRuns = 19;
const Chi2Family kChi2(kRuns);
const double kAlpha = kChi2.alpha();
constexpr int kSamples = 1000000;

// A scene with the given shapes (JSON array body) and lights, no camera-facing requirements.
// The camera is at the origin, so that rendering space (loader/camera_reader.h) is the scene
// file's and the tests can ask the lights about the points they name.
LoadedScene makeScene(const std::string& shapes, const std::string& lights = "",
                      const std::string& selection = "power") {
    return loadSceneText(R"({"render": {"resolution": [4, 4], "light_selection": ")" + selection +
                         R"("},
        "camera": {"position": [0, 0, 0], "look_at": [0, 0, -1]},
        "shapes": [)" + shapes +
                         "]" + (lights.empty() ? "" : R"(, "lights": [)" + lights + "]") + "}");
}

bool hitsLight(const Scene& scene, const Light& light, const Vec3& origin, const Vec3& dir,
               SurfaceHit* hit) {
    if (!scene.intersect(Ray{origin, dir}, hit)) return false;
    return hit->shape != nullptr && hit->shape->areaLight() == &light;
}

// The band and resolution of a DirectionHistogram (the χ² tooling integrates the expected
// counts, refining cells on the outline of the light).
struct DirectionCells {
    int zCells, phiCells;
    double zMin;
    DirectionHistogram histogram() const { return DirectionHistogram(zCells, phiCells, zMin); }
};

// --- The light-sampling χ² run -----------------------------------------------------------------

struct LightRun {
    Chi2Outcome outcome;
    int failedSamples = 0;    // sample() returned false
    double expectedMass = 0;  // ∫ pdf over the directions that hit the light
};

// Samples `light` from `reference` and histograms the directions in a frame whose +z is `axis`;
// the expected density in a direction is light.pdf() at the point a ray from `reference`
// hits, or zero if the ray misses the light. `pdfOf` may replace light.pdf (negative controls).
LightRun runLightChi2(const Scene& scene, const Light& light, const Vec3& reference,
                      const Vec3& axis, const DirectionCells& cells, uint64_t seed,
                      const std::function<double(const SurfaceHit&)>& pdfOf = nullptr) {
    const Frame frame(normalize(axis));
    LightRun run;
    DirectionHistogram h = cells.histogram();
    for (int i = 0; i < kSamples; ++i) {
        LightSample ls;
        if (!light.sample(reference, uniform2(seed, i), 0.0f, &ls)) {
            ++run.failedSamples;
            continue;
        }
        h.add(frame.toLocal(ls.direction));
    }
    const auto pdf = [&](const Vec3& local) -> double {
        SurfaceHit hit;
        if (!hitsLight(scene, light, reference, normalize(frame.toWorld(local)), &hit)) return 0;
        return pdfOf ? pdfOf(hit) : light.pdf(reference, hit);
    };
    const double accepted = kSamples - run.failedSamples;
    const std::vector<double> expected = h.expected(pdf, accepted);
    for (double e : expected)
        run.expectedMass += e / accepted;
    run.outcome = chi2GoodnessOfFit(h.counts(), expected);
    return run;
}

void expectLightFits(const LightRun& run, const std::string& what) {
    EXPECT_EQ(run.failedSamples, 0) << what;
    EXPECT_NEAR(run.expectedMass, 1.0, 2e-3) << what << ": the pdf over the light's directions";
    kChi2.expectFits(run.outcome, what);
}

// 1 − cos θmax of the cone subtended by a sphere at distance d = ratio · radius (in double).
double sphereCone(double ratio) {
    const double sin2 = 1.0 / (ratio * ratio);
    return sin2 / (1.0 + std::sqrt(1.0 - sin2));
}

// Cells for a density whose support is the cone z ≥ 1 − c: 24 z-cells of which the cone spans
// 20.5, so its edge is in the middle of a cell.
DirectionCells coneCells(double oneMinusCos) {
    const double dz = oneMinusCos / 20.5;
    return {24, 48, std::max(-1.0, 1.0 - 24 * dz)};
}

// Smallest z (in the frame of `axis`) of the directions from `reference` to `points`, minus a
// margin: the band of a histogram covering a planar light.
double lowestZ(const Vec3& reference, const Vec3& axis, const std::vector<Vec3>& points) {
    double z = 1;
    for (const Vec3& p : points)
        z = std::min(z, double(dot(normalize(p - reference), axis)));
    return std::max(-1.0, z - 0.02);
}

// --- Sphere lights ----------------------------------------------------------------------------

const char* kSphere =
    R"({"type": "sphere", "center": [0.5, -0.25, 1], "radius": 0.8,
        "emission": {"radiance": [1, 2, 3]}})";
const Vec3 kSphereCenter(0.5f, -0.25f, 1.0f);
constexpr float kSphereRadius = 0.8f;

// Reference points outside at d = 1.05 r (very wide cone), 3 r, 30 r (narrow cone), along an
// oblique direction.
class SphereFromOutside : public ::testing::TestWithParam<float> {};

TEST_P(SphereFromOutside, DirectionsFollowPdf) {
    const LoadedScene s = makeScene(kSphere);
    const Light& light = *s.scene->lights()[0];
    const float d = GetParam() * kSphereRadius;
    const Vec3 reference = kSphereCenter + normalize(Vec3(1, 2, -3)) * d;
    const double c = sphereCone(GetParam());
    const LightRun run = runLightChi2(*s.scene, light, reference, kSphereCenter - reference,
                                      coneCells(c), 10 + uint64_t(GetParam() * 100));
    expectLightFits(run, "sphere from outside, d = " + std::to_string(GetParam()) + " r");
}

INSTANTIATE_TEST_SUITE_P(Distances, SphereFromOutside, ::testing::Values(1.05f, 3.0f, 30.0f));

// Inside a two-sided emissive sphere the light falls back to area sampling: directions over the
// whole sphere, with density dist² / (A cos θ).
TEST(SphereFromInside, DirectionsFollowPdf) {
    const LoadedScene s = makeScene(
        R"({"type": "sphere", "center": [0.5, -0.25, 1], "radius": 0.8,
            "emission": {"radiance": [1, 2, 3], "two_sided": true}})");
    const Light& light = *s.scene->lights()[0];
    const Vec3 reference = kSphereCenter + Vec3(0.3f, -0.2f, 0.4f);
    const LightRun run = runLightChi2(*s.scene, light, reference, kSphereCenter - reference,
                                      DirectionCells{40, 50, -1.0}, 20);
    expectLightFits(run, "two-sided sphere from inside");
}

// A one-sided sphere emits outwards only: from inside, every sample carries no radiance.
TEST(SphereFromInside, OneSidedSphereGivesNoSamples) {
    const LoadedScene s = makeScene(kSphere);
    const Light& light = *s.scene->lights()[0];
    for (int i = 0; i < 1000; ++i) {
        LightSample ls;
        EXPECT_FALSE(light.sample(kSphereCenter + Vec3(0.1f, 0.2f, 0), uniform2(21, i), 0, &ls));
    }
}

// --- Planar lights ------------------------------------------------------------------------------

const char* kQuad =
    R"({"type": "quad", "corner": [-1, -0.5, 0], "edge_u": [2, 0, 0], "edge_v": [0, 1.5, 0.3],
        "emission": {"radiance": [1, 2, 3]}})";
const Vec3 kQuadCorner(-1, -0.5f, 0), kQuadU(2, 0, 0), kQuadV(0, 1.5f, 0.3f);

TEST(QuadLight, DirectionsFollowPdf) {
    const LoadedScene s = makeScene(kQuad);
    const Light& light = *s.scene->lights()[0];
    const Vec3 normal = normalize(cross(kQuadU, kQuadV));
    const Vec3 reference(0.3f, 0.4f, 1.2f);  // in front, above the quad's interior
    const Vec3 axis = -normal;
    const std::vector<Vec3> corners = {kQuadCorner, kQuadCorner + kQuadU, kQuadCorner + kQuadV,
                                       kQuadCorner + kQuadU + kQuadV};
    const LightRun run = runLightChi2(*s.scene, light, reference, axis,
                                      {30, 48, lowestZ(reference, axis, corners)}, 30);
    expectLightFits(run, "quad");
}

TEST(QuadLight, OneSidedQuadGivesNoSamplesFromBehind) {
    const LoadedScene s = makeScene(kQuad);
    const Light& light = *s.scene->lights()[0];
    for (int i = 0; i < 1000; ++i) {
        LightSample ls;
        EXPECT_FALSE(light.sample(Vec3(0.3f, 0.4f, -1.0f), uniform2(31, i), 0, &ls));
    }
}

const Vec3 kDiskCenter(0.2f, -0.1f, 0.4f);
const Vec3 kDiskNormal = normalize(Vec3(0.3f, -0.2f, 1.0f));
constexpr float kDiskRadius = 0.8f;
std::string diskJson(bool twoSided) {
    return R"({"type": "disk", "center": [0.2, -0.1, 0.4], "normal": [0.3, -0.2, 1],
               "radius": 0.8, "emission": {"radiance": [1, 2, 3], "two_sided": )" +
           std::string(twoSided ? "true" : "false") + "}}";
}
std::vector<Vec3> diskRim() {
    const Frame f(kDiskNormal);
    std::vector<Vec3> rim;
    for (int k = 0; k < 360; ++k)
        rim.push_back(kDiskCenter +
                      f.toWorld(Vec3(std::cos(k * kPi / 180), std::sin(k * kPi / 180), 0)) *
                          kDiskRadius);
    return rim;
}

// Off-axis reference in front of the disk: the projection of the disk is not a cone.
TEST(DiskLight, DirectionsFollowPdf) {
    const LoadedScene s = makeScene(diskJson(false));
    const Light& light = *s.scene->lights()[0];
    const Frame f(kDiskNormal);
    const Vec3 reference = kDiskCenter + f.toWorld(Vec3(0.5f, 0.2f, 0.7f));
    const LightRun run = runLightChi2(*s.scene, light, reference, -kDiskNormal,
                                      {30, 48, lowestZ(reference, -kDiskNormal, diskRim())}, 40);
    expectLightFits(run, "disk");
}

// A two-sided disk seen from behind, far off-axis (the reference's projection is outside the
// disk, so the support does not contain the pole).
TEST(DiskLight, TwoSidedDiskFromBehindFollowsPdf) {
    const LoadedScene s = makeScene(diskJson(true));
    const Light& light = *s.scene->lights()[0];
    const Frame f(kDiskNormal);
    const Vec3 reference = kDiskCenter + f.toWorld(Vec3(1.1f, -0.4f, -0.5f));
    const Vec3 axis = kDiskCenter - reference;
    DirectionCells cells{30, 48, lowestZ(reference, normalize(axis), diskRim())};
    const LightRun run = runLightChi2(*s.scene, light, reference, axis, cells, 41);
    expectLightFits(run, "two-sided disk from behind");
}

// A triangle-mesh emitter (built directly: no mesh file needed): a roof of six triangles of
// different areas, two-sided, seen from above so that every ray meets at most one triangle.
// Area sampling picks a triangle by area (Distribution1D) and a point in it (Heitz's map).
MeshData roofMesh() {
    MeshData m;
    m.positions = {{-1, 0, 0.5f}, {1, 0, 0.5f}, {-1, 1, 0},     {0.4f, 1, 0},
                   {1, 1, 0},     {-1, -1, 0},  {-0.5f, -1, 0}, {1, -1, 0}};
    m.indices = {0, 1, 3, 0, 3, 2, 1, 4, 3,   // the y > 0 side
                 0, 6, 1, 0, 5, 6, 1, 6, 7};  // the y < 0 side
    return m;
}
double roofArea() {
    const MeshData m = roofMesh();
    double a = 0;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
        const Vec3 &p0 = m.positions[m.indices[t]], &p1 = m.positions[m.indices[t + 1]],
                   &p2 = m.positions[m.indices[t + 2]];
        a += 0.5 * length(cross(p1 - p0, p2 - p0));
    }
    return a;
}
struct BuiltScene {
    std::unique_ptr<Scene> scene;
};
BuiltScene makeRoofScene() {
    SceneBuilder b;
    b.setCamera(CameraSettings{}, 4, 4);
    b.addShape(std::make_unique<TriangleMesh>(roofMesh()), nullptr, Rgb(1, 2, 3), true);
    return {b.build(LightSelection::Power)};
}
const Vec3 kRoofReference(0.2f, 0.3f, 2.0f);

TEST(MeshLight, DirectionsFollowPdf) {
    const BuiltScene s = makeRoofScene();
    const Light& light = *s.scene->lights()[0];
    const Vec3 axis(0, 0, -1);
    const LightRun run =
        runLightChi2(*s.scene, light, kRoofReference, axis,
                     {30, 48, lowestZ(kRoofReference, axis, roofMesh().positions)}, 45);
    expectLightFits(run, "triangle-mesh roof");
}

// --- Polygon lights ---------------------------------------------------------------------------

// A convex pentagon with fan triangles of different areas, in a tilted plane: (x, y) in the
// frame of kPolygonNormal around kPolygonCenter.
const Vec3 kPolygonCenter(0.2f, -0.1f, 0.4f);
const Vec3 kPolygonNormal = normalize(Vec3(-0.3f, 0.2f, 1.0f));
const std::vector<Vec2> kPolygonXY = {
    {-1, -0.6f}, {0.8f, -0.8f}, {1.2f, 0.3f}, {0.2f, 1}, {-0.9f, 0.5f}};
std::vector<Vec3> polygonVertices() {
    const Frame f(kPolygonNormal);
    std::vector<Vec3> v;
    for (const Vec2& p : kPolygonXY)
        v.push_back(kPolygonCenter + f.toWorld(Vec3(p.x, p.y, 0)));
    return v;
}
// Shoelace area of the (x, y) outline.
double polygonArea() {
    double a = 0;
    for (size_t i = 0; i < kPolygonXY.size(); ++i) {
        const Vec2 &p = kPolygonXY[i], &q = kPolygonXY[(i + 1) % kPolygonXY.size()];
        a += 0.5 * (double(p.x) * q.y - double(q.x) * p.y);
    }
    return a;
}
std::string polygonJson(const std::string& sampling = "solid_angle") {
    std::string vertices;
    char buffer[128];
    for (const Vec3& v : polygonVertices()) {
        std::snprintf(buffer, sizeof buffer, "%s[%.9g, %.9g, %.9g]", vertices.empty() ? "" : ", ",
                      v.x, v.y, v.z);
        vertices += buffer;
    }
    return R"({"type": "polygon", "vertices": [)" + vertices + R"(], "sampling": ")" + sampling +
           R"(", "emission": {"radiance": [1, 2, 3]}})";
}

// In front of the polygon, placed so that every vertex is over a tenth of a cell from the edges
// of the histogram's cells (a vertex just across a cell edge would put a sliver of the support
// in a cell the quadrature sees as empty).
const Vec3 kPolygonReference =
    kPolygonCenter + Frame(kPolygonNormal).toWorld(Vec3(0.4f, 0.1f, 0.9f));

// Is (x, y) inside the convex, counter-clockwise outline?
bool insidePolygon(const Vec2& p) {
    for (size_t i = 0; i < kPolygonXY.size(); ++i) {
        const Vec2 &a = kPolygonXY[i], &b = kPolygonXY[(i + 1) % kPolygonXY.size()];
        if ((b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x) < 0) return false;
    }
    return true;
}

// Sampled by solid angle: from kPolygonReference, and from just above the polygon (the fan's
// spherical triangles then cover most of the hemisphere); and by area from kPolygonReference.
struct PolygonView {
    const char* id;
    const char* name;
    Vec3 reference;
    uint64_t seed;
    const char* sampling = "solid_angle";
};
class PolygonLight : public ::testing::TestWithParam<PolygonView> {};

TEST_P(PolygonLight, DirectionsFollowPdf) {
    const LoadedScene s = makeScene(polygonJson(GetParam().sampling));
    const Light& light = *s.scene->lights()[0];
    const Vec3 reference = GetParam().reference;
    const Vec3 axis = -kPolygonNormal;
    const DirectionCells cells{30, 48, lowestZ(reference, axis, polygonVertices())};
    for (const Vec3& v : polygonVertices()) {
        const Vec3 w = Frame(axis).toLocal(normalize(v - reference));
        const double phi = std::atan2(w.y, w.x) + (w.y < 0 ? 2 * M_PI : 0);
        for (double f : {(w.z - cells.zMin) / (1 - cells.zMin) * cells.zCells,
                         phi / (2 * M_PI) * cells.phiCells})
            EXPECT_GT(std::min(f - std::floor(f), std::ceil(f) - f), 0.1)
                << "vertex near a cell edge";
    }
    const LightRun run = runLightChi2(*s.scene, light, reference, axis, cells, GetParam().seed);
    expectLightFits(run, GetParam().name);
}

const PolygonView kPolygonViews[] = {
    {"Reference", "polygon", kPolygonReference, 47},
    {"Close", "polygon, close",
     kPolygonCenter + Frame(kPolygonNormal).toWorld(Vec3(-0.1f, 0.2f, 0.05f)), 46},
    {"ByArea", "polygon, by area", kPolygonReference, 48, "area"}};
INSTANTIATE_TEST_SUITE_P(Views, PolygonLight, ::testing::ValuesIn(kPolygonViews),
                         [](const auto& p) { return std::string(p.param.id); });

// The density is 1/Ω, with Ω the solid angle in closed form for a square seen on its axis,
// 4 asin(a²/(a² + d²)) for half-side a at distance d; far away (Ω < 10⁻⁴ sr) the polygon is
// sampled by area, and the density is that of area sampling.
TEST(PolygonLightPdf, IsOneOverSolidAngleOrByAreaWhenFar) {
    const LoadedScene s = makeScene(
        R"({"type": "polygon", "vertices": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
            "emission": {"radiance": 1}})");
    const Light& light = *s.scene->lights()[0];
    for (double d : {0.01, 0.5, 1.0, 30.0, 150.0, 1000.0}) {
        const Vec3 reference(0, 0, float(d));
        SurfaceHit hit;
        ASSERT_TRUE(
            s.scene->intersect(Ray{reference, normalize(Vec3(0.3f, -0.4f, 0) - reference)}, &hit));
        const double omega = 4 * std::asin(1 / (1 + d * d));
        const double expected =
            omega >= Polygon::kMinSolidAngle
                ? 1 / omega
                : areaToSolidAngle(0.25f, reference, hit.position, hit.geometricNormal);
        EXPECT_NEAR(light.pdf(reference, hit), expected, 1e-5 * expected) << "d = " << d;
    }
}

// Area samples, in the polygon's (x, y) coordinates, against the uniform density 1/A on it
// (or against `pdf`, for the negative control).
Chi2Outcome polygonAreaChi2(const std::function<double(const Vec2&)>& pdf) {
    const Polygon polygon(polygonVertices());
    const Frame f(kPolygonNormal);
    PlaneHistogram h(40, 40, -1.1, 1.3, -0.9, 1.1);
    for (int i = 0; i < kSamples; ++i) {
        const ShapeSample s = polygon.sampleArea(uniform2(48, i));
        const Vec3 local = f.toLocal(s.position - kPolygonCenter);
        EXPECT_LT(std::abs(local.z), 1e-5f);
        h.add(Vec2(local.x, local.y));
    }
    return chi2GoodnessOfFit(h.counts(), h.expected(pdf, kSamples));
}

TEST(PolygonShape, AreaSamplesAreUniform) {
    const Polygon polygon(polygonVertices());
    EXPECT_NEAR(polygon.area(), polygonArea(), 1e-5 * polygonArea());
    EXPECT_GT(dot(polygon.normal(), kPolygonNormal), 0.99999f) << "right-hand rule on the order";
    kChi2.expectFits(
        polygonAreaChi2([](const Vec2& p) { return insidePolygon(p) ? 1 / polygonArea() : 0.0; }),
        "polygon area samples");
}

// Validation tolerances are relative to the polygon's size: a vertex on an edge (collinear)
// and a lift of 1e-5 of the size are accepted at any scale; 1e-3 is not, nor a clockwise dent.
TEST(PolygonShape, ValidationIsRelativeToSize) {
    for (float scale : {1e-4f, 1.0f, 1e4f}) {
        const auto square = [&](float lift) {
            return std::vector<Vec3>{Vec3(0, 0, 0) * scale, Vec3(1, 0, 0) * scale,
                                     Vec3(2, 0, lift) * scale, Vec3(2, 2, 0) * scale,
                                     Vec3(0, 2, 0) * scale};
        };
        EXPECT_FALSE(checkConvexPolygon(square(2e-5f))) << scale;
        const auto lifted = checkConvexPolygon(square(2e-3f));
        ASSERT_TRUE(lifted) << scale;
        EXPECT_EQ(lifted->vertex, 2);
        std::vector<Vec3> dented = square(0);
        dented[1] = Vec3(1, 0.1f, 0) * scale;
        const auto dent = checkConvexPolygon(dented);
        ASSERT_TRUE(dent) << scale;
        EXPECT_EQ(dent->vertex, 1);
    }
}

// uv: a rectangle given as a polygon has the uv of the same quad; hit points agree.
TEST(PolygonShape, RectangleUvIsTheQuads) {
    const LoadedScene quad = makeScene(kQuad);
    const LoadedScene polygon = makeScene(
        R"({"type": "polygon", "vertices": [[-1, -0.5, 0], [1, -0.5, 0], [1, 1, 0.3], [-1, 1, 0.3]],
            "emission": {"radiance": [1, 2, 3]}})");
    const Vec3 normal = normalize(cross(kQuadU, kQuadV));
    for (int i = 0; i < 1000; ++i) {
        const Vec2 st = uniform2(49, i);
        const Vec3 target = kQuadCorner + kQuadU * st.x + kQuadV * st.y;
        const Ray ray{target + normal * 2 + Vec3(0.1f, 0.2f, 0),
                      normalize(-normal * 2 - Vec3(0.1f, 0.2f, 0))};
        SurfaceHit a, b;
        ASSERT_TRUE(quad.scene->intersect(ray, &a));
        ASSERT_TRUE(polygon.scene->intersect(ray, &b));
        EXPECT_NEAR(a.uv.x, st.x, 1e-5f);
        EXPECT_NEAR(b.uv.x, a.uv.x, 1e-5f);
        EXPECT_NEAR(b.uv.y, a.uv.y, 1e-5f);
        EXPECT_LT(length(a.position - b.position), 1e-5f);
        EXPECT_GT(dot(b.geometricNormal, normal), 0.99999f);
    }
}

// --- Negative controls ------------------------------------------------------------------------

// Cone samples judged with the area-sampling density (a sample/pdf strategy mismatch).
TEST(LightChi2NegativeControl, SphereConeSamplesRejectAreaSamplingPdf) {
    const LoadedScene s = makeScene(kSphere);
    const Light& light = *s.scene->lights()[0];
    const Vec3 reference = kSphereCenter + normalize(Vec3(1, 2, -3)) * (3.0f * kSphereRadius);
    const float area = 4 * kPi * kSphereRadius * kSphereRadius;
    const LightRun run =
        runLightChi2(*s.scene, light, reference, kSphereCenter - reference,
                     coneCells(sphereCone(3.0)), 310, [&](const SurfaceHit& hit) {
                         return double(areaToSolidAngle(1.0f / area, reference, hit.position,
                                                        hit.geometricNormal));
                     });
    kChi2.expectRejects(run.outcome, "sphere cone samples vs area-sampling pdf");
}

// Quad samples judged with a density that forgets the cosine of the area-to-solid-angle
// conversion, renormalised so that only the shape of the density is wrong.
TEST(LightChi2NegativeControl, QuadSamplesRejectPdfWithoutCosine) {
    const LoadedScene s = makeScene(kQuad);
    const Light& light = *s.scene->lights()[0];
    const Vec3 normal = normalize(cross(kQuadU, kQuadV));
    const Vec3 reference(0.3f, 0.4f, 1.2f);
    const std::vector<Vec3> corners = {kQuadCorner, kQuadCorner + kQuadU, kQuadCorner + kQuadV,
                                       kQuadCorner + kQuadU + kQuadV};
    const DirectionCells cells{30, 48, lowestZ(reference, -normal, corners)};
    const auto noCosine = [&](const SurfaceHit& hit) {
        return double(lengthSquared(hit.position - reference)) / length(cross(kQuadU, kQuadV));
    };
    const auto pdfAt = [&](const Vec3& local) -> double {
        SurfaceHit hit;
        const Frame f(-normal);
        return hitsLight(*s.scene, light, reference, normalize(f.toWorld(local)), &hit)
                   ? noCosine(hit)
                   : 0.0;
    };
    double norm = 0;
    for (double e : cells.histogram().expected(pdfAt, 1.0))
        norm += e;
    const LightRun run = runLightChi2(*s.scene, light, reference, -normal, cells, 30,
                                      [&](const SurfaceHit& hit) { return noCosine(hit) / norm; });
    kChi2.expectRejects(run.outcome, "quad samples vs pdf without cosine");
}

// Solid-angle samples of the polygon, seen from close by, judged with the area-sampling density.
TEST(LightChi2NegativeControl, PolygonSolidAngleSamplesRejectAreaSamplingPdf) {
    const LoadedScene s = makeScene(polygonJson());
    const Light& light = *s.scene->lights()[0];
    const PolygonView& view = kPolygonViews[1];
    const Vec3 axis = -kPolygonNormal;
    const LightRun run =
        runLightChi2(*s.scene, light, view.reference, axis,
                     {30, 48, lowestZ(view.reference, axis, polygonVertices())}, view.seed,
                     [&](const SurfaceHit& hit) {
                         return double(areaToSolidAngle(1 / float(polygonArea()), view.reference,
                                                        hit.position, hit.geometricNormal));
                     });
    kChi2.expectRejects(run.outcome, "polygon solid-angle samples vs area-sampling pdf");
}

// Polygon area samples judged with the density of picking each fan triangle with equal
// probability (the triangles' areas differ): the fan selection by area is under test.
TEST(LightChi2NegativeControl, PolygonSamplesRejectEqualFanTriangles) {
    const auto cross2 = [](const Vec2& a, const Vec2& b, const Vec2& c) {
        return double(b.x - a.x) * (c.y - a.y) - double(b.y - a.y) * (c.x - a.x);
    };
    const size_t triangles = kPolygonXY.size() - 2;
    const auto equalFan = [&](const Vec2& p) {
        const Vec2& v0 = kPolygonXY[0];
        for (size_t k = 1; k + 1 < kPolygonXY.size(); ++k) {
            const Vec2 &a = kPolygonXY[k], &b = kPolygonXY[k + 1];
            if (cross2(v0, a, p) >= 0 && cross2(a, b, p) >= 0 && cross2(b, v0, p) >= 0)
                return 1 / (triangles * 0.5 * cross2(v0, a, b));
        }
        return 0.0;
    };
    kChi2.expectRejects(polygonAreaChi2(equalFan), "polygon area samples vs equal fan triangles");
}

// --- Sample values: radiance, pdf at the sampled point ------------------------------------------

struct LightCase {
    std::string name, shape;
    Vec3 reference;
};

// For 10⁴ samples: the ray towards ls.direction hits the light at ls.position, the radiance is
// the emitted radiance, and ls.pdf equals light.pdf() there.
TEST(LightSamples, RadianceAndPdfMatchTheLight) {
    const std::vector<LightCase> cases = {
        {"sphere, near", kSphere, kSphereCenter + normalize(Vec3(1, 2, -3)) * 0.9f},
        {"sphere, far", kSphere, kSphereCenter + normalize(Vec3(1, 2, -3)) * 24.0f},
        {"sphere, inside two-sided",
         R"({"type": "sphere", "center": [0.5, -0.25, 1], "radius": 0.8,
             "emission": {"radiance": [1, 2, 3], "two_sided": true}})",
         kSphereCenter + Vec3(0.3f, -0.2f, 0.4f)},
        {"quad", kQuad, Vec3(0.3f, 0.4f, 1.2f)},
        {"disk", diskJson(false), kDiskCenter + Frame(kDiskNormal).toWorld(Vec3(0.5f, 0.2f, 0.7f))},
        {"disk, two-sided from behind", diskJson(true),
         kDiskCenter + Frame(kDiskNormal).toWorld(Vec3(1.1f, -0.4f, -0.5f))},
        {"polygon", polygonJson(), kPolygonReference},
    };
    for (const LightCase& c : cases) {
        const LoadedScene s = makeScene(c.shape);
        const Light& light = *s.scene->lights()[0];
        EXPECT_FALSE(light.isDelta());
        int worst = 0;
        double worstError = 0;
        for (int i = 0; i < 10000; ++i) {
            LightSample ls;
            ASSERT_TRUE(light.sample(c.reference, uniform2(50, i), 0, &ls)) << c.name;
            EXPECT_EQ(ls.radiance, Rgb(1, 2, 3)) << c.name;
            EXPECT_FALSE(ls.isDelta);
            EXPECT_NEAR(length(ls.direction), 1.0f, 1e-5f) << c.name;
            const Vec3 toPoint = ls.position - c.reference;
            EXPECT_NEAR(dot(normalize(toPoint), ls.direction), 1.0f, 1e-6f) << c.name;
            SurfaceHit hit;
            ASSERT_TRUE(hitsLight(*s.scene, light, c.reference, ls.direction, &hit))
                << c.name << ": the sampled direction misses the light";
            EXPECT_LT(length(hit.position - ls.position), 1e-4f * (1 + length(toPoint))) << c.name;
            EXPECT_GT(std::abs(dot(ls.normal, hit.geometricNormal)), 0.9999f) << c.name;
            const float pdf = light.pdf(c.reference, hit);
            const double error = std::abs(pdf - ls.pdf) / ls.pdf;
            if (error > worstError) {
                worstError = error;
                worst = i;
            }
        }
        EXPECT_LT(worstError, 1e-3)
            << c.name << ": sample " << worst << " has sample pdf ≠ light->pdf";
    }
    // The mesh roof, built without the loader.
    const BuiltScene roof = makeRoofScene();
    const Light& light = *roof.scene->lights()[0];
    for (int i = 0; i < 10000; ++i) {
        LightSample ls;
        ASSERT_TRUE(light.sample(kRoofReference, uniform2(51, i), 0, &ls));
        EXPECT_EQ(ls.radiance, Rgb(1, 2, 3));
        SurfaceHit hit;
        ASSERT_TRUE(hitsLight(*roof.scene, light, kRoofReference, ls.direction, &hit));
        EXPECT_LT(length(hit.position - ls.position), 1e-4f);
        EXPECT_NEAR(light.pdf(kRoofReference, hit), ls.pdf, 1e-3f * ls.pdf);
    }
    EXPECT_NEAR(light.power().g, 2 * kPi * roofArea() * 2, 1e-4f * light.power().g);
}

// Directions at the very edge of a narrow cone can miss the sphere by rounding; the sample must
// still succeed, with a point that faces the reference and lies (nearly) along the direction.
// (Regression: the tangent-point fallback's normal faced away half the time, and AreaLight
// dropped the sample as back-facing: ~1.6e-5 of all samples at d = 3000 r.)
TEST(LightSamples, GrazingConeEdgeDirectionsStillSample) {
    const LoadedScene s = makeScene(kSphere);
    const Light& light = *s.scene->lights()[0];
    for (float ratio : {3.0f, 30.0f, 300.0f, 3000.0f}) {
        const Vec3 reference = kSphereCenter + normalize(Vec3(1, 2, -3)) * (ratio * kSphereRadius);
        int failed = 0;
        for (int k = 1; k <= 64; ++k)
            for (int j = 0; j < 200; ++j) {
                LightSample ls;
                const Vec2 u(1.0f - float(k) * 0x1p-24f, (j + 0.5f) / 200);
                if (!light.sample(reference, u, 0, &ls)) {
                    ++failed;
                    continue;
                }
                EXPECT_GT(dot(ls.normal, reference - ls.position), 0.0f);
                const Vec3 toPoint = normalize(ls.position - reference);
                EXPECT_GT(dot(toPoint, ls.direction), 1.0f - 1e-6f);
            }
        EXPECT_EQ(failed, 0) << "d = " << ratio << " r: " << failed
                             << " of 12800 cone-edge samples failed";
    }
}

// --- Point lights, power ------------------------------------------------------------------------

TEST(PointLight, GivesIntensityOverDistanceSquared) {
    const LoadedScene s =
        makeScene("", R"({"type": "point", "position": [1, 2, 3], "intensity": [4, 5, 6]})");
    ASSERT_EQ(s.scene->lights().size(), 1u);
    const Light& light = *s.scene->lights()[0];
    EXPECT_TRUE(light.isDelta());
    for (const Vec3 reference : {Vec3(0, 0, 0), Vec3(1, 2, 1), Vec3(-3, 5, 10)}) {
        LightSample ls;
        ASSERT_TRUE(light.sample(reference, Vec2(0.3f, 0.7f), 0, &ls));
        const float d2 = lengthSquared(Vec3(1, 2, 3) - reference);
        EXPECT_TRUE(ls.isDelta);
        EXPECT_EQ(ls.pdf, 1.0f);
        EXPECT_NEAR(ls.radiance.r, 4 / d2, 1e-6f * 4 / d2);
        EXPECT_NEAR(ls.radiance.g, 5 / d2, 1e-6f * 5 / d2);
        EXPECT_NEAR(ls.radiance.b, 6 / d2, 1e-6f * 6 / d2);
        EXPECT_NEAR(length(ls.direction), 1.0f, 1e-6f);
        EXPECT_NEAR(dot(ls.direction, normalize(Vec3(1, 2, 3) - reference)), 1.0f, 1e-6f);
        EXPECT_EQ(ls.position, Vec3(1, 2, 3));
        SurfaceHit anything;
        anything.position = Vec3(1, 2, 3);
        EXPECT_EQ(light.pdf(reference, anything), 0.0f);
    }
    EXPECT_NEAR(light.power().r, 4 * 4 * kPi, 1e-4f);
    EXPECT_NEAR(light.power().b, 6 * 4 * kPi, 1e-4f);
}

// Spot lights: I(θ) = I₀ inside falloff_start, 0 outside cone_angle, smoothstep in cos θ
// between (the test's own statement of the documented profile).
double spotProfile(double cosTheta, double coneDegrees, double startDegrees) {
    const double cosCone = std::cos(coneDegrees * M_PI / 180);
    const double cosStart = std::cos(startDegrees * M_PI / 180);
    if (cosTheta >= cosStart) return 1;
    if (cosTheta <= cosCone) return 0;
    const double x = (cosTheta - cosCone) / (cosStart - cosCone);
    return x * x * (3 - 2 * x);
}

struct SpotCase {
    double cone, start;  // degrees
};
const Vec3 kSpotPosition(0.5f, 1, -0.5f), kSpotTarget(0.2f, -1, 0.3f);
const Rgb kSpotIntensity(4, 5, 6);

LoadedScene spotScene(const SpotCase& c, bool withStart = true) {
    return makeScene("", R"({"type": "spot", "position": [0.5, 1, -0.5], "look_at": [0.2, -1, 0.3],
                             "intensity": [4, 5, 6], "cone_angle": )" +
                             std::to_string(c.cone) +
                             (withStart ? R"(, "falloff_start": )" + std::to_string(c.start) : "") +
                             "}");
}

// The radiant intensity radiance · d² seen from a point at distance d in the direction that
// makes angle θ with the axis (0 when sample() gives nothing).
double spotIntensity(const Light& light, double cosTheta, double phi, double d, int channel) {
    const Frame f(normalize(kSpotTarget - kSpotPosition));
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    const Vec3 w = f.toWorld(
        Vec3(float(sinTheta * std::cos(phi)), float(sinTheta * std::sin(phi)), float(cosTheta)));
    LightSample ls;
    if (!light.sample(kSpotPosition + w * float(d), Vec2(0.3f, 0.6f), 0, &ls)) return 0;
    EXPECT_TRUE(ls.isDelta);
    EXPECT_EQ(ls.pdf, 1.0f);
    EXPECT_EQ(ls.position, kSpotPosition);
    EXPECT_NEAR(dot(ls.direction, -w), 1.0f, 1e-6f);
    return ls.radiance[channel] * d * d;
}

TEST(SpotLight, IntensityFollowsTheProfile) {
    for (const SpotCase c : {SpotCase{30, 20}, SpotCase{30, 30}, SpotCase{90, 0}, SpotCase{2, 1}}) {
        const LoadedScene s = spotScene(c);
        const Light& light = *s.scene->lights()[0];
        EXPECT_TRUE(light.isDelta());
        const double cosCone = std::cos(c.cone * M_PI / 180);
        for (int k = 0; k <= 400; ++k) {
            // Angles from 0 to 1.2 × the cone, and the distances 0.5 and 3.
            const double theta = 1.2 * c.cone * M_PI / 180 * k / 400;
            const double expected = 5 * spotProfile(std::cos(theta), c.cone, c.start);
            for (double d : {0.5, 3.0}) {
                const double i = spotIntensity(light, std::cos(theta), 0.1 * k, d, 1);
                EXPECT_NEAR(i, expected, 1e-5 * 5 + 2e-3 * expected)
                    << "cone " << c.cone << ", start " << c.start << ", θ = " << theta;
            }
        }
        EXPECT_EQ(spotIntensity(light, cosCone - 1e-3, 0, 1, 1), 0) << "outside the cone";
        EXPECT_EQ(spotIntensity(light, -0.5, 0, 1, 1), 0) << "behind";
    }
    // falloff_start defaults to cone_angle: a hard edge.
    const LoadedScene hard = spotScene({25, 0}, false);
    const double cos25 = std::cos(25 * M_PI / 180);
    EXPECT_NEAR(spotIntensity(*hard.scene->lights()[0], cos25 + 1e-4, 0, 1, 0), 4, 1e-5);
    EXPECT_EQ(spotIntensity(*hard.scene->lights()[0], cos25 - 1e-4, 0, 1, 0), 0);
}

// power() is the intensity integrated over the sphere, measured through sample(): a midpoint
// rule in (cos θ, φ) split at cos θc and cos θs, where the profile has kinks.
TEST(SpotLight, PowerIsTheIntegralOfTheIntensity) {
    for (const SpotCase c : {SpotCase{30, 20}, SpotCase{30, 30}, SpotCase{90, 0}, SpotCase{2, 1},
                             SpotCase{60, 59.9}}) {
        const LoadedScene s = spotScene(c);
        const Light& light = *s.scene->lights()[0];
        const double breaks[] = {-1, std::cos(c.cone * M_PI / 180), std::cos(c.start * M_PI / 180),
                                 1};
        constexpr int kMu = 400, kPhi = 16;
        double integral = 0;
        for (int piece = 0; piece < 3; ++piece) {
            const double lo = breaks[piece], hi = breaks[piece + 1];
            for (int a = 0; a < kMu; ++a)
                for (int b = 0; b < kPhi; ++b)
                    integral += spotIntensity(light, lo + (a + 0.5) / kMu * (hi - lo),
                                              (b + 0.5) / kPhi * 2 * M_PI, 1.0, 2) *
                                (hi - lo) / kMu * (2 * M_PI / kPhi);
        }
        const double closedForm =
            6 * M_PI * (2 - std::cos(c.start * M_PI / 180) - std::cos(c.cone * M_PI / 180));
        EXPECT_NEAR(light.power().b, integral, 1e-4 * integral) << c.cone << ", " << c.start;
        EXPECT_NEAR(light.power().b, closedForm, 1e-5 * closedForm) << c.cone << ", " << c.start;
        EXPECT_NEAR(light.power().r / light.power().b, 4.0 / 6, 1e-6);
    }
}

TEST(AreaLight, PowerIsPiTimesAreaTimesRadiance) {
    struct Case {
        std::string shape;
        float area;
        bool twoSided;
    };
    const float quadArea = length(cross(kQuadU, kQuadV));
    const std::vector<Case> cases = {
        {kSphere, 4 * kPi * kSphereRadius * kSphereRadius, false},
        {kQuad, quadArea, false},
        {R"({"type": "quad", "corner": [-1, -0.5, 0], "edge_u": [2, 0, 0],
             "edge_v": [0, 1.5, 0.3], "emission": {"radiance": [1, 2, 3], "two_sided": true}})",
         quadArea, true},
        {diskJson(false), kPi * kDiskRadius * kDiskRadius, false},
        {diskJson(true), kPi * kDiskRadius * kDiskRadius, true},
        {polygonJson(), float(polygonArea()), false},
    };
    for (const Case& c : cases) {
        const LoadedScene s = makeScene(c.shape);
        const Rgb power = s.scene->lights()[0]->power();
        const float k = kPi * c.area * (c.twoSided ? 2.0f : 1.0f);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(power[ch], k * float(ch + 1), 1e-5f * k * float(ch + 1)) << c.shape;
    }
}

// --- Light selection ----------------------------------------------------------------------------

const char* kFourLightShapes =
    R"({"type": "sphere", "center": [0, 0, 0], "radius": 0.5, "emission": {"radiance": 1}},
       {"type": "quad", "corner": [2, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0],
        "emission": {"radiance": [4, 1, 1]}},
       {"type": "disk", "center": [-2, 0, 0], "radius": 0.3,
        "emission": {"radiance": 2, "two_sided": true}})";
const char* kPointLight = R"({"type": "point", "position": [0, 3, 0], "intensity": 0.2})";

Chi2Outcome selectionChi2(const LightSelector& selector, std::span<const Light* const> lights,
                          const std::vector<double>& pmf, uint64_t seed) {
    std::vector<double> counts(lights.size(), 0.0), expected(lights.size());
    const Vec3 reference(0.1f, 0.2f, 0.3f);
    for (int i = 0; i < kSamples; ++i) {
        float p;
        const Light* l = selector.select(uniform(seed, i, 0), reference, &p);
        counts[l->index()] += 1;
    }
    for (size_t i = 0; i < pmf.size(); ++i)
        expected[i] = pmf[i] * kSamples;
    return chi2GoodnessOfFit(counts, expected);
}

TEST(LightSelection, PmfsAreUniformOrProportionalToPower) {
    const LoadedScene s = makeScene(kFourLightShapes, kPointLight);
    const auto lights = s.scene->lights();
    ASSERT_EQ(lights.size(), 4u);
    double totalPower = 0;
    for (const Light* l : lights)
        totalPower += l->power().luminance();
    const auto uniformSelector = makeLightSelector(LightSelection::Uniform, lights);
    const auto powerSelector = makeLightSelector(LightSelection::Power, lights);
    const Vec3 reference(0.1f, 0.2f, 0.3f);
    double sumUniform = 0, sumPower = 0;
    for (size_t i = 0; i < lights.size(); ++i) {
        const Light& l = *lights[i];
        EXPECT_EQ(l.index(), int(i));
        EXPECT_FLOAT_EQ(uniformSelector->pmf(l, reference), 0.25f);
        const double expected = l.power().luminance() / totalPower;
        EXPECT_NEAR(powerSelector->pmf(l, reference), expected, 1e-6 * expected) << i;
        // The scene's own selector uses the document's "power" default.
        EXPECT_EQ(s.scene->lightSelector().pmf(l, reference), powerSelector->pmf(l, reference));
        sumUniform += uniformSelector->pmf(l, reference);
        sumPower += powerSelector->pmf(l, reference);
    }
    EXPECT_NEAR(sumUniform, 1.0, 1e-6);
    EXPECT_NEAR(sumPower, 1.0, 1e-6);
    // select() reports the pmf of the light it picks.
    for (int i = 0; i < 1000; ++i) {
        float p;
        const Light* l = powerSelector->select((i + 0.5f) / 1000, reference, &p);
        ASSERT_NE(l, nullptr);
        EXPECT_EQ(p, powerSelector->pmf(*l, reference));
    }
    const LoadedScene u = makeScene(kFourLightShapes, kPointLight, "uniform");
    for (const Light* l : u.scene->lights())
        EXPECT_FLOAT_EQ(u.scene->lightSelector().pmf(*l, reference), 0.25f);
}

TEST(LightSelection, SelectedLightsFollowPmf) {
    const LoadedScene s = makeScene(kFourLightShapes, kPointLight);
    const auto lights = s.scene->lights();
    double totalPower = 0;
    for (const Light* l : lights)
        totalPower += l->power().luminance();
    std::vector<double> uniformPmf(lights.size(), 0.25), powerPmf;
    for (const Light* l : lights)
        powerPmf.push_back(l->power().luminance() / totalPower);
    kChi2.expectFits(
        selectionChi2(*makeLightSelector(LightSelection::Uniform, lights), lights, uniformPmf, 60),
        "uniform light selection");
    kChi2.expectFits(
        selectionChi2(*makeLightSelector(LightSelection::Power, lights), lights, powerPmf, 61),
        "light selection by power");
}

TEST(LightChi2NegativeControl, PowerSelectionIsNotUniform) {
    const LoadedScene s = makeScene(kFourLightShapes, kPointLight);
    const auto lights = s.scene->lights();
    kChi2.expectRejects(selectionChi2(*makeLightSelector(LightSelection::Power, lights), lights,
                                      std::vector<double>(lights.size(), 0.25), 61),
                        "power selection vs uniform pmf");
}

}  // namespace
}  // namespace rr::test
