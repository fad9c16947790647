// A new material needs only the Material interface (eval, pdf, sample, lobes): what a technique
// asks beyond it is a capability the material may implement (scene/lobe_peaks.h). One written
// here, knowing no technique:
//  - renders with path_mis: a diffuse convex sphere under a constant environment L reflects
//    albedo·L;
//  - two_stage with analytic peaks (the default) refuses a scene that has it, alone or in a mix,
//    with a ConfigError at the estimator's "peaks"; with "peaks": "bsdf" it is accepted, and a
//    scene of materials that know their peaks is accepted with either (controls).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "config/config_error.h"
#include "loader/factories.h"
#include "sampling/warps.h"
#include "scene/lights/constant_environment.h"
#include "scene/materials/lambert.h"
#include "scene/materials/mix.h"
#include "scene/shapes/sphere.h"
#include "support/maps.h"
#include "support/scene_testing.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

// Lambertian reflection written as a new material would be, with nothing but the interface.
class PlainDiffuse final : public Material {
  public:
    explicit PlainDiffuse(float albedo) : albedo_(albedo) {}

    Rgb eval(const ShadingContext&, const Vec3& wo, const Vec3& wi) const override {
        return wo.z * wi.z > 0 ? Rgb(albedo_ * kInvPi * std::abs(wi.z)) : Rgb(0.0f);
    }
    float pdf(const ShadingContext&, const Vec3& wo, const Vec3& wi) const override {
        return wo.z * wi.z > 0 ? std::abs(wi.z) * kInvPi : 0.0f;
    }
    bool sample(const ShadingContext&, const Vec3& wo, float, Vec2 u,
                BsdfSample* out) const override {
        Vec3 wi = squareToCosineHemisphere(u);
        out->pdf = cosineHemispherePdf(wi);
        if (!(out->pdf > 0)) return false;
        if (wo.z < 0) wi.z = -wi.z;  // two-sided
        out->wi = wi;
        out->weight = Rgb(albedo_);
        out->lobe = kReflection | kDiffuse;
        return true;
    }
    uint8_t lobes() const override { return kReflection | kDiffuse; }

  private:
    float albedo_;
};

constexpr float kAlbedo = 0.6f;
constexpr int kSize = 16;

// A unit sphere 4 in front of the camera, filling the middle of the image, made of `material`,
// lit by `light`.
std::shared_ptr<const Scene> sphereScene(std::unique_ptr<Material> material,
                                         std::unique_ptr<Light> light) {
    SceneBuilder builder;
    const Material* m = builder.addMaterial(std::move(material));
    builder.addShape(std::make_unique<Sphere>(Vec3(0, 0, -4), 1.0f), m, Rgb(0.0f), false);
    builder.addLight(std::move(light));
    CameraSettings camera;
    camera.verticalFovDegrees = 30;
    builder.setCamera(camera, kSize, kSize);
    return builder.build(LightSelection::Power);
}

// A lat-long map of a sky and a dim floor, as two_stage needs.
std::unique_ptr<Light> latLongMap() {
    const auto file = writeRgbExr(scratchDirectory() / "new_material_sky.exr", 32, 16,
                                  [](int, int row) { return Rgb(row < 8 ? 1.0f : 0.1f); });
    const Json description = {
        {"type", "environment"}, {"file", file.string()}, {"layout", "latlong"}};
    ObjectReader reader(description, "/lights/0");
    return makeLight(reader, AssetResolver::standard(TEST_SCENES_DIR), Transform());
}

// The scene's integrator from its JSON object, prepared for `scene` (ConfigError when it
// refuses the scene).
BuiltIntegrator preparedIntegrator(const Scene& scene, const Json& description) {
    ObjectReader reader(description, "/integrator");
    BuiltIntegrator built = techniqueRegistry().makeIntegrator(reader, PathSettings{});
    built.integrator->prepare(scene);
    return built;
}

TEST(NewMaterial, RendersWithPathMis) {
    LoadedScene loaded;
    loaded.scene = sphereScene(std::make_unique<PlainDiffuse>(kAlbedo),
                               std::make_unique<ConstantEnvironment>(Rgb(1.0f)));
    BuiltIntegrator built = preparedIntegrator(*loaded.scene, {{"type", "path_mis"}});
    loaded.integrator = std::move(built.integrator);
    loaded.schedule = std::move(built.schedule);
    loaded.render.width = loaded.render.height = kSize;
    const TestRender r = renderScene(loaded, 64);
    // The middle 4 × 4 pixels lie on the sphere.
    for (int c = 0; c < 3; ++c) {
        const Estimate e = regionMean(r.film, c, 6, 6, 10, 10);
        EXPECT_GT(e.standardError, 0) << c;
        EXPECT_NEAR(e.mean, kAlbedo, 4 * e.standardError + 1e-6) << c;
    }
}

const Json kTwoStageAnalytic = {{"type", "direct"}, {"estimator", {{"type", "two_stage"}}}};
const Json kTwoStageBsdfPeaks = {{"type", "direct"},
                                 {"estimator", {{"type", "two_stage"}, {"peaks", "bsdf"}}}};

void expectRefusedAtPeaks(const Scene& scene, const char* what) {
    try {
        preparedIntegrator(scene, kTwoStageAnalytic);
        ADD_FAILURE() << what << ": two_stage with analytic peaks accepted it";
    } catch (const ConfigError& e) {
        EXPECT_EQ(e.pointer(), "/integrator/estimator/peaks") << what << ": " << e.what();
    }
}

TEST(NewMaterial, TwoStageWithAnalyticPeaksRefusesIt) {
    const auto plain = sphereScene(std::make_unique<PlainDiffuse>(kAlbedo), latLongMap());
    expectRefusedAtPeaks(*plain, "the material alone");
    EXPECT_NO_THROW(preparedIntegrator(*plain, kTwoStageBsdfPeaks));

    // A mix knows its peaks only when both its parts do (its parts belong to the test here, so
    // that the scene's one material is the mix).
    const PlainDiffuse part(kAlbedo);
    const Lambert lambert{Rgb(kAlbedo)};
    const auto mixed = sphereScene(
        std::make_unique<MixMaterial>(&part, &lambert, constantTexture(0.5f)), latLongMap());
    expectRefusedAtPeaks(*mixed, "in a mix");

    // Control: a material that knows its peaks.
    const auto known = sphereScene(std::make_unique<Lambert>(Rgb(kAlbedo)), latLongMap());
    EXPECT_NO_THROW(preparedIntegrator(*known, kTwoStageAnalytic));
    EXPECT_NO_THROW(preparedIntegrator(*known, kTwoStageBsdfPeaks));
}

}  // namespace
}  // namespace rr::test
