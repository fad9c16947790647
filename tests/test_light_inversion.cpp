// InvertibleLight::invertSample (scene/invertible_light.h), the inverse of Light::sample (TAIS's
// point-on-light importance map lives on the uniform coordinates u that sample() warps, and MIS
// needs the u behind a point found by BSDF sampling): round trips u → sample(reference, u) →
// invertSample(reference, direction, position) → u' for every light that inverts, from several
// reference points; the lights that cannot invert refuse; and negative controls (the wrong
// reference point, the wrong rotation) that the round-trip check must reject.
//
// The check, per u for which sample() succeeds: invertSample succeeds, and either
//  - u' = u within a tolerance per set-up (comments there: the direction of a float point seen
//    from a float reference is known to a few ε·(|reference| + |point|)/distance, and the
//    inverse scales that by its derivative), or
//  - u' is another preimage of the sampled direction: sample(reference, u') gives the same
//    direction up to rounding (forwardTolerance). This is what invertSample promises ("the u for
//    which sample yields the point"); it is needed where sample() is not injective or the
//    inverse is ill-conditioned: the axis of a cone or the poles of a sphere, where the azimuth
//    is lost; the azimuth's seam, u.y = 0 and u.y → 1 being one direction; the lat-long map's
//    seam and poles; the probe's rim. Such round trips are counted and must stay few.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/rgb_image_io.h"
#include "loader/asset_resolver.h"
#include "math/frame.h"
#include "scene/invertible_light.h"
#include "scene/lights/area_light.h"
#include "scene/lights/constant_environment.h"
#include "scene/lights/env_layout.h"
#include "scene/lights/environment_map.h"
#include "scene/lights/point_light.h"
#include "scene/lights/spot_light.h"
#include "scene/shapes/disk.h"
#include "scene/shapes/polygon.h"
#include "scene/shapes/quad.h"
#include "scene/shapes/sphere.h"
#include "scene/shapes/triangle_mesh.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

constexpr float kEpsilon = 0x1p-24f;  // unit roundoff of float

// --- The round-trip check ------------------------------------------------------------------------

// Stratified u: one jittered point in each cell of a 64 × 64 grid, plus the edges of [0,1)² and
// the floats next to them (where warps divide by zero, lose the azimuth or wrap around).
std::vector<Vec2> stratifiedU(uint64_t seed) {
    constexpr int kGrid = 64;
    std::vector<Vec2> us;
    for (int i = 0; i < kGrid; ++i)
        for (int j = 0; j < kGrid; ++j) {
            const Vec2 jitter = uniform2(seed, uint64_t(i) * kGrid + j);
            us.push_back({(float(i) + jitter.x) / kGrid, (float(j) + jitter.y) / kGrid});
        }
    const float edges[] = {0.0f, kEpsilon, 1e-4f, 0.5f, 1 - 1e-4f, 1 - kEpsilon};
    for (float a : edges)
        for (float b : edges)
            us.push_back({a, b});
    return us;
}

float angleBetween(const Vec3& a, const Vec3& b) {
    return 2 * std::asin(std::min(1.0f, length(a - b) / 2));
}

// How far sample(reference, u') may land from the sampled direction `w` (point `p`) when u' is
// a preimage of w: the rounding of w itself (its point, seen from the reference, is known to
// a few ε·(|reference| + |p|)/distance), and the rounding of u' (a float, a few ε from the exact
// preimage), times how fast sample() moves with u there (forward differences, a step of 2⁻²⁰).
float forwardTolerance(const Light& light, const Vec3& reference, const Vec3& p, Vec2 uBack) {
    const float rounding =
        4 * kEpsilon *
        (1 + (maxAbsComponent(reference) + maxAbsComponent(p)) / length(p - reference));
    LightSample at;
    if (!light.sample(reference, uBack, 0, &at)) return 0;
    float speed = 0;  // |∂w/∂u|, the larger of the two columns
    for (int axis = 0; axis < 2; ++axis) {
        Vec2 moved = uBack;
        float& c = axis == 0 ? moved.x : moved.y;
        c = c < 0.5f ? c + 0x1p-20f : c - 0x1p-20f;
        const float step = std::abs(c - (axis == 0 ? uBack.x : uBack.y));
        LightSample there;
        if (light.sample(reference, moved, 0, &there))
            speed = std::max(speed, angleBetween(there.direction, at.direction) / step);
    }
    return 4 * rounding + 4 * kEpsilon * speed;
}

struct RoundTrips {
    int samples = 0;  // u for which sample() succeeded
    int refused = 0;  // of those, invertSample refused
    // Refused where the direction has zero density: an environment map's sample at the edge of
    // its texel (u at the edges of [0,1)² make the point inside the texel 0) whose direction
    // rounds across the edge into a texel of zero weight. A sample carries the density of the
    // texel it was drawn in (environment_map.h), so such a sample exists; no u yields its
    // rounded direction. Allowed for the edge cases only.
    int refusedAtEdge = 0;
    int recovered = 0;         // |u' − u|∞ ≤ tolerance
    int otherPreimage = 0;     // not recovered, but sample(u') gives the same direction
    int failed = 0;            // neither
    float worstRecovered = 0;  // max |u' − u|∞ of the recovered
    float worstForward = 0;    // max angle / forwardTolerance of the other preimages
};

// Samples `light` from `reference` and inverts with `inverse` from `inverseReference` (the
// same, except in negative controls).
RoundTrips roundTrips(const Light& light, const Vec3& reference, const InvertibleLight& inverse,
                      const Vec3& inverseReference, float tolerance, uint64_t seed) {
    RoundTrips r;
    for (const Vec2& u : stratifiedU(seed)) {
        LightSample ls;
        if (!light.sample(reference, u, 0, &ls)) continue;
        ++r.samples;
        Vec2 back;
        if (!inverse.invertSample(inverseReference, ls.direction, ls.position, &back)) {
            const bool edge = std::min({u.x, u.y, 1 - u.x, 1 - u.y}) <= 2 * kEpsilon;
            const bool zeroDensity =
                light.isInfinite() && light.directionPdf(inverseReference, ls.direction) == 0;
            ++(edge && zeroDensity ? r.refusedAtEdge : r.refused);
            continue;
        }
        EXPECT_TRUE(back.x >= 0 && back.x < 1 && back.y >= 0 && back.y < 1)
            << back.x << ", " << back.y;
        const float error = std::max(std::abs(back.x - u.x), std::abs(back.y - u.y));
        if (error <= tolerance) {
            ++r.recovered;
            r.worstRecovered = std::max(r.worstRecovered, error);
            continue;
        }
        LightSample again;
        const float allowed = forwardTolerance(light, reference, ls.position, back);
        if (light.sample(reference, back, 0, &again) &&
            angleBetween(again.direction, ls.direction) <= allowed) {
            ++r.otherPreimage;
            r.worstForward =
                std::max(r.worstForward, angleBetween(again.direction, ls.direction) / allowed);
        } else {
            ++r.failed;
        }
    }
    return r;
}

// At most 1% of the round trips may need the other-preimage criterion (measured: at most 20 of
// 4132, all but three among the 36 edge-case u; those three next to a cone's axis and on the
// probe's rim).
void expectRoundTrips(const RoundTrips& r, const std::string& what) {
    std::printf(
        "%-44s %4d samples: %4d recovered (max |Δu| %.2g), %2d other preimage (max %.2g "
        "of the tolerance), %d failed, %d refused (%d more at the edges of [0,1)², rounded into "
        "zero density)\n",
        what.c_str(), r.samples, r.recovered, r.worstRecovered, r.otherPreimage, r.worstForward,
        r.failed, r.refused, r.refusedAtEdge);
    EXPECT_GT(r.samples, 4000) << what;
    EXPECT_EQ(r.refused, 0) << what;
    EXPECT_LE(r.refusedAtEdge, 36) << what << ": the edge cases of stratifiedU";
    EXPECT_EQ(r.failed, 0) << what;
    EXPECT_LE(r.otherPreimage, r.samples / 100) << what;
}

// --- Area lights ---------------------------------------------------------------------------------

const Vec3 kSphereCenter(0.3f, -0.2f, 0.5f);

// Outside the sphere (cone sampling) the tolerances follow the cone: u.x = (1 − cos θ)/(1 − cos
// θmax) changes by about 2/θmax per radian, and the direction is known to ~ε·|p|/distance. Far
// (d = 30 r, θmax ≈ 1.9°) 1e-4; at 3 r 1e-5; at 1.01 r, with points 0.01 r from the reference,
// 3e-5. At 1.0002 r the nearest points are 2e-4 from the reference, where the direction of a
// point with coordinates ~1 is known only to ~5e-4 rad: 2e-3. Inside (area sampling, uniform on the
// sphere) u follows the normal (p − c)/r, known to ~ε: 1e-5. The azimuth near the cone's axis or
// the sphere's poles (Δu.y ~ error / sin θ) is left to the other-preimage criterion.
struct SphereCase {
    float distance;  // of the reference from the centre, in radii
    float tolerance;
};
const SphereCase kSphereCases[] = {{30.0f, 1e-4f}, {3.0f, 1e-5f}, {1.01f, 3e-5f}, {1.0002f, 2e-3f},
                                   {0.99f, 1e-5f}, {0.5f, 1e-5f}, {0.0f, 1e-5f}};

TEST(LightInversion, SphereRoundTrips) {
    const Sphere sphere(kSphereCenter, 1.0f);
    const AreaLight light(&sphere, Rgb(1.0f), true);
    const Vec3 towards = normalize(Vec3(0.4f, 0.7f, -0.2f));
    for (const SphereCase& c : kSphereCases) {
        const Vec3 reference = kSphereCenter + towards * c.distance;
        expectRoundTrips(roundTrips(light, reference, light, reference, c.tolerance, 1),
                         "sphere, reference at " + std::to_string(c.distance) + " r");
    }
}

// Quads and disks are sampled by area; the inverse reads u off the point itself (its (s, t), or
// the inverse concentric map of its position in the disk), whatever the reference: the point's
// rounding, a few ε of its coordinates, gives |Δu| of a few 1e-7. Tolerance 1e-6.
TEST(LightInversion, QuadAndDiskRoundTrips) {
    const Quad quad(Vec3(-1, -1, 2), Vec3(2, 0, 0.3f), Vec3(0, 1.5f, 0));
    const AreaLight quadLight(&quad, Rgb(1.0f), true);
    // Behind, 0.01 above the middle, 0.0015 off the plane just past an edge, far in front.
    for (const Vec3& reference :
         {Vec3(0, 0, -5), Vec3(0, -0.25f, 2.16f), Vec3(1.01f, 0, 2.3f), Vec3(0.3f, 0.2f, 30)}) {
        expectRoundTrips(roundTrips(quadLight, reference, quadLight, reference, 1e-6f, 2), "quad");
    }
    const Disk disk(Vec3(0.5f, 1, -1), Vec3(0.2f, 1, 0.1f), 0.7f);
    const AreaLight diskLight(&disk, Rgb(1.0f), true);
    // Behind, 0.01 above the centre, past the rim, far in front.
    for (const Vec3& reference :
         {Vec3(0, 0, -5), Vec3(0.5f, 1.01f, -1), Vec3(1.3f, 1, -1), Vec3(0, 5, 0)}) {
        expectRoundTrips(roundTrips(diskLight, reference, diskLight, reference, 1e-6f, 3), "disk");
    }
}

// --- Infinite lights -----------------------------------------------------------------------------

// Uniform sphere sampling; u.x = (1 − z)/2 is exact up to the rounding of z: tolerance 1e-6.
TEST(LightInversion, ConstantEnvironmentRoundTrips) {
    ConstantEnvironment light(Rgb(1.0f));
    EXPECT_TRUE(invertibleLight(light));
    light.preprocess(Vec3(0.0f), 2.0f);
    for (const Vec3& reference : {Vec3(0.0f), Vec3(0.5f, -1, 0.3f)}) {
        expectRoundTrips(roundTrips(light, reference, light, reference, 1e-6f, 4),
                         "constant environment");
    }
}

// A small map with a few bright texels, a dim background and texels of zero weight (which
// sample() skips, so the round trip must not land in them), bright texels on the lat-long seam
// and the pole row.
RgbImage syntheticImage(int width, int height) {
    RgbImage image;
    image.width = width;
    image.height = height;
    for (int row = 0; row < height; ++row)
        for (int col = 0; col < width; ++col) {
            Rgb p(0.002f);
            if ((col * 7 + row * 3) % 11 == 0) p = Rgb(0.0f);
            if (col == 5 && row == 3) p = Rgb(50);
            if (col == 0 && row == 0) p = Rgb(20);
            if (col == width - 1 && row == height / 2) p = Rgb(8, 1, 1);
            if (col == width / 2 && row == height / 2) p = Rgb(3);
            image.pixels.push_back(p);
        }
    return image;
}

// v rotated by `angle` about the unit `axis` (Rodrigues).
Vec3 rotate(const Vec3& v, const Vec3& axis, float angle) {
    return v * std::cos(angle) + cross(axis, v) * std::sin(angle) +
           axis * (dot(axis, v) * (1 - std::cos(angle)));
}
Frame rotate(const Frame& f, const Vec3& axis, float angle) {
    Frame r;
    r.s = rotate(f.s, axis, angle);
    r.t = rotate(f.t, axis, angle);
    r.n = rotate(f.n, axis, angle);
    return r;
}

// A rotation that moves every axis.
const Frame kRotation =
    Frame::fromNormalAndTangent(normalize(Vec3(0.3f, 0.8f, -0.5f)), Vec3(1, 0.2f, 0));

std::unique_ptr<EnvironmentMap> makeMap(RgbImage image, const std::string& layout,
                                        const Frame& rotation) {
    auto map = std::make_unique<EnvironmentMap>(std::move(image), makeEnvLayout(layout), Rgb(1.0f),
                                                rotation);
    map->preprocess(Vec3(0.0f), 1.0f);
    return map;
}

// The image point of a direction is known to a few ε (atan2 of rounded coordinates), and
// Distribution2D::invert scales an error in the image by the density of the image's cells in u
// (width · the column's probability, height · the row's): at most 16 here; near the lat-long
// poles s is known only to ~ε/sin θ. Tolerance 1e-5.
TEST(LightInversion, SyntheticEnvironmentMapRoundTrips) {
    for (const char* layout : {"latlong", "probe"}) {
        const bool latlong = std::string(layout) == "latlong";
        const auto map = makeMap(syntheticImage(16, latlong ? 8 : 16), layout, kRotation);
        for (const Vec3& reference : {Vec3(0.0f), Vec3(0.5f, -0.3f, 0.2f)}) {
            expectRoundTrips(roundTrips(*map, reference, *map, reference, 1e-5f, 5),
                             std::string("synthetic map, ") + layout);
        }
    }
}

std::optional<std::filesystem::path> galileo() {
    return AssetResolver::standard(TEST_SCENES_DIR).resolve("envmaps/galileo_probe.hdr");
}

// Debevec's Galileo probe (1000 × 1000), from the asset search path: skipped when absent,
// unless REQUIRE_ASSETS=1. Its windows are bright: a few texels hold most of the probability,
// and there the image's rounding error is scaled by 1000 × the column's probability.
// Tolerance 1e-4.
class GalileoInversion : public ::testing::TestWithParam<std::string> {
  protected:
    void SetUp() override {
        file_ = galileo();
        if (file_) return;
        const std::string where = AssetResolver::standard(TEST_SCENES_DIR).describe();
        const char* required = std::getenv("REQUIRE_ASSETS");
        if (required != nullptr && std::string(required) == "1")
            FAIL() << "REQUIRE_ASSETS=1 but no envmaps/galileo_probe.hdr in " << where;
        GTEST_SKIP() << "envmaps/galileo_probe.hdr is not on the asset search path " << where;
    }
    std::optional<std::filesystem::path> file_;
};

TEST_P(GalileoInversion, RoundTrips) {
    const auto map = makeMap(readRgbImage(*file_), GetParam(), kRotation);
    expectRoundTrips(roundTrips(*map, Vec3(0.0f), *map, Vec3(0.0f), 1e-4f, 6),
                     "Galileo, " + GetParam());
}

INSTANTIATE_TEST_SUITE_P(Layouts, GalileoInversion, ::testing::Values("probe", "latlong"),
                         [](const auto& p) { return p.param; });

// Directions no u yields are refused: the lat-long poles (no solid angle), the probe's rim
// (the single direction −Z, no solid angle) and a texel of zero weight.
TEST(LightInversion, EnvironmentMapRefusesDirectionsOfZeroDensity) {
    const auto latlong = makeMap(syntheticImage(16, 8), "latlong", Frame());
    const auto probe = makeMap(syntheticImage(16, 16), "probe", Frame());
    Vec2 u;
    EXPECT_FALSE(latlong->invertSample(Vec3(0.0f), Vec3(0, 1, 0), Vec3(0.0f), &u));
    EXPECT_FALSE(latlong->invertSample(Vec3(0.0f), Vec3(0, -1, 0), Vec3(0.0f), &u));
    EXPECT_FALSE(probe->invertSample(Vec3(0.0f), Vec3(0, 0, -1), Vec3(0.0f), &u));
    // The texels of zero weight (the pattern of syntheticImage), away from the poles.
    const RgbImage image = syntheticImage(16, 8);
    for (int row = 1; row < 7; ++row)
        for (int col = 0; col < 16; ++col) {
            if (!image.pixels[size_t(row) * 16 + col].isBlack()) continue;
            Vec3 w;
            float jacobian;
            ASSERT_TRUE(
                latlong->layout().direction({(col + 0.5f) / 16, (row + 0.5f) / 8}, &w, &jacobian));
            EXPECT_EQ(latlong->directionPdf(Vec3(0.0f), w), 0.0f);
            EXPECT_FALSE(latlong->invertSample(Vec3(0.0f), w, Vec3(0.0f), &u))
                << col << ", " << row;
        }
}

// --- Lights that cannot invert -------------------------------------------------------------------

TEST(LightInversion, LightsWithoutAnInverseRefuse) {
    Vec2 u;
    const Vec3 reference(0, 0, 0), direction(0, 0, 1), point(0, 0, 3);
    const PointLight pointLight(point, Rgb(1.0f));
    EXPECT_FALSE(invertibleLight(pointLight)) << "point light";
    const SpotLight spot(point, Vec3(0, 0, -1), Rgb(1.0f), 0.5f, 0.3f);
    EXPECT_FALSE(invertibleLight(spot)) << "spot light";

    const std::vector<Vec3> square = {Vec3(-1, -1, 3), Vec3(1, -1, 3), Vec3(1, 1, 3),
                                      Vec3(-1, 1, 3)};
    const Polygon polygon(square);
    const AreaLight polygonLight(&polygon, Rgb(1.0f), true);
    EXPECT_FALSE(polygonLight.invertSample(reference, direction, point, &u)) << "polygon";
    EXPECT_FALSE(invertibleLight(polygonLight));
    MeshData mesh;
    mesh.positions = square;
    mesh.indices = {0, 1, 2, 0, 2, 3};
    const TriangleMesh triangles(mesh);
    const AreaLight meshLight(&triangles, Rgb(1.0f), true);
    EXPECT_FALSE(meshLight.invertSample(reference, direction, point, &u)) << "triangle mesh";
    EXPECT_FALSE(invertibleLight(meshLight));

    // Moving shapes: their samples depend on the time, which the inverse is not given.
    Sphere sphere(Vec3(0, 0, 4), 1.0f);
    Quad quad(Vec3(-1, -1, 3), Vec3(2, 0, 0), Vec3(0, 2, 0));
    Disk disk(Vec3(0, 0, 3), Vec3(0, 0, -1), 1.0f);
    for (Shape* shape :
         {static_cast<Shape*>(&sphere), static_cast<Shape*>(&quad), static_cast<Shape*>(&disk)}) {
        const AreaLight light(shape, Rgb(1.0f), true);
        EXPECT_TRUE(light.invertSample(reference, direction, point, &u)) << "static";
        EXPECT_TRUE(invertibleLight(light)) << "static";
        shape->setMotion(Vec3(0.1f, 0, 0));
        EXPECT_FALSE(light.invertSample(reference, direction, point, &u)) << "moving";
        EXPECT_FALSE(invertibleLight(light)) << "moving";
    }
}

// --- Negative controls ---------------------------------------------------------------------------

// Inverting from the wrong reference point (0.3 r away) gives the u of another cone: the check
// must reject nearly every round trip.
TEST(LightInversionNegativeControl, WrongReferenceFails) {
    const Sphere sphere(kSphereCenter, 1.0f);
    const AreaLight light(&sphere, Rgb(1.0f), true);
    const Vec3 reference = kSphereCenter + Vec3(0, 0, 3);
    const RoundTrips r =
        roundTrips(light, reference, light, reference + Vec3(0.3f, 0, 0), 1e-5f, 7);
    std::printf("wrong reference: %d of %d round trips fail\n", r.failed, r.samples);
    EXPECT_GT(r.failed, r.samples * 9 / 10);
}

// Inverting with a map rotated by 5° more: the check must reject nearly every round trip.
TEST(LightInversionNegativeControl, WrongRotationFails) {
    const auto map = makeMap(syntheticImage(16, 8), "latlong", kRotation);
    const auto turned = makeMap(syntheticImage(16, 8), "latlong",
                                rotate(kRotation, normalize(Vec3(1, 1, 0)), 5 * kPi / 180));
    const RoundTrips r = roundTrips(*map, Vec3(0.0f), *turned, Vec3(0.0f), 1e-5f, 8);
    std::printf("wrong rotation: %d of %d round trips fail, %d refused\n", r.failed, r.samples,
                r.refused);
    EXPECT_GT(r.failed + r.refused, r.samples * 9 / 10);
}

}  // namespace
}  // namespace rr::test
