#include <cmath>

#include "config/type_table.h"
#include "io/rgb_image_io.h"
#include "loader/asset_files.h"
#include "loader/factories.h"
#include "scene/lights/constant_environment.h"
#include "scene/lights/environment_map.h"
#include "scene/lights/latlong_resampling.h"
#include "scene/lights/point_light.h"
#include "scene/lights/spot_light.h"

namespace rr {

namespace {

constexpr float kRadiansPerDegree = kPi / 180;

const KeyTable kPointKeys{
    "light/point",
    "isotropic point light of radiant intensity I (irradiance I cos θ / d²); only next-event "
    "estimation finds it",
    {key("position").vector().means("where it is"),
     key("intensity").colour().means("radiant intensity I")}};

const KeyTable kSpotKeys{
    "light/spot",
    "a point light with I(θ) = I₀ inside `falloff_start`, 0 beyond `cone_angle`, smoothstep in "
    "cos θ between (pbrt-v4's falloff); power π I₀ (2 − cos θs − cos θc)",
    {key("position").vector().means("where it is"),
     key("look_at").vector().means("a point on its axis (≠ position)"),
     key("intensity").colour().means("on-axis radiant intensity I₀"),
     key("cone_angle")
         .number(Range{0, 90, true, false})
         .means("half-angle in degrees where the intensity reaches 0"),
     key("falloff_start")
         .number(Range::closed(0, 90))
         .defaultSays("`cone_angle` (a hard edge)")
         .means("half-angle in degrees where the falloff begins, ≤ `cone_angle`")}};

const KeyTable kEnvironmentKeys{
    "light/environment",
    "light from every direction: a constant `radiance`, or a map from `file` (see Environment "
    "maps); power π r² ∫ L dω with r the scene's bounding radius",
    {key("radiance").colour().optional().means("constant radiance (not with `file`)"),
     key("file").string().optional().means(
         "a map (.hdr or .exr) on the asset search path (not with `radiance`)"),
     key("layout")
         .choice({"latlong", "probe"})
         .defaultSays("required with `file`")
         .means("the map's parameterisation"),
     key("scale").colour().byDefault(1.0).means("multiplies the map"),
     key("transform")
         .object("transform")
         .optional()
         .means("rotations only: the map's direction d appears at R d"),
     key("latlong_width")
         .integer(Range::closed(16, 16384))
         .optional()
         .means("`probe` only: resample once at load into a lat-long map of this (even) width "
                "and half its height, which every technique then sees"),
     key("sampling")
         .choice({"luminance", "cosine", "uniform"})
         .byDefault("luminance")
         .estimandNeutral()
         .means("how light samples draw directions: ∝ luminance × solid angle (pbrt-v1's "
                "infinitesample; uniform for a constant), cosine-weighted about the receiver's "
                "normal (pbrt-v1's infinite), or uniform (1/4π)")}};

std::unique_ptr<Light> makeSpot(ObjectReader& j, const AssetResolver&, const Transform& place) {
    const Vec3d from = j.point("position");
    const Vec3 position = place.point(from);
    const Vec3 axis = toFloat(j.point("look_at") - from);
    if (!(length(axis) > 0)) j.fail("look_at", "must differ from position");
    const Rgb intensity = j.colour("intensity");
    const float cone = j.real("cone_angle");
    const float falloffStart = j.getFloat("falloff_start", cone, j.spec("falloff_start").range);
    if (falloffStart > cone)
        j.fail("falloff_start", "must not exceed cone_angle (" + std::to_string(cone) + ")");
    return std::make_unique<SpotLight>(position, normalize(axis), intensity,
                                       cone * kRadiansPerDegree, falloffStart * kRadiansPerDegree);
}

// The rotation of an environment map: a proper rotation (orthonormal, determinant +1) and no
// translation, as the map's frame; anything else is an error at "transform".
Frame readRotation(ObjectReader& j) {
    const Transform t = readTransform(j, "transform");
    Frame r;  // the images of the map's X, Y and Z axes
    r.s = t.vector(Vec3(1, 0, 0));
    r.t = t.vector(Vec3(0, 1, 0));
    r.n = t.vector(Vec3(0, 0, 1));
    float scale = 0;
    const bool rotation = t.isSimilarity(&scale) && std::abs(scale - 1) < 1e-4f &&
                          dot(cross(r.s, r.t), r.n) > 0 && t.point(Vec3d{}) == Vec3(0.0f);
    if (!rotation) j.fail("transform", "an environment map takes rotations only");
    r.s = normalize(r.s);
    r.t = normalize(r.t);
    r.n = normalize(r.n);
    return r;
}

// "sampling": how light samples draw directions (env_sampling.h); `luminance` by default
// (a constant environment: uniform, the same thing).
EnvSampling readEnvSampling(ObjectReader& j) {
    const std::string name = j.choice("sampling");
    if (name == "cosine") return EnvSampling::Cosine;
    return name == "uniform" ? EnvSampling::Uniform : EnvSampling::Luminance;
}

std::unique_ptr<Light> makeEnvironmentMap(ObjectReader& j, const AssetResolver& assets) {
    const std::string layoutName = j.choice("layout");
    const Rgb scale = j.colour("scale");
    const Frame toWorld = readRotation(j);
    // "latlong_width": the probe resampled once into a lat-long map of that width, which is
    // then the light every technique sees (two-stage sampling works on the lat-long grid).
    int latLongWidth = 0;
    if (j.has("latlong_width")) {
        if (layoutName != "probe")
            j.fail("latlong_width", "resampling to lat-long applies to \"layout\": \"probe\"");
        latLongWidth = static_cast<int>(j.integer("latlong_width"));
        if (latLongWidth % 2 != 0)
            j.fail("latlong_width", "must be even (the map's height is half its width)");
    }
    RgbImage image = readImageAsset(j, "file", assets, "environment map");
    if (layoutName == "probe" && image.width != image.height)
        j.fail("layout", "an angular probe must be square, " + j.getString("file") + " is " +
                             std::to_string(image.width) + "x" + std::to_string(image.height));
    std::unique_ptr<EnvLayout> layout = makeEnvLayout(layoutName);
    if (latLongWidth > 0) {
        image = resampleToLatLong(image, *layout, latLongWidth);
        layout = makeEnvLayout("latlong");
    }
    return std::make_unique<EnvironmentMap>(std::move(image), std::move(layout), scale, toWorld,
                                            readEnvSampling(j));
}

// {"radiance": L} is a constant environment, {"file": …} a map.
std::unique_ptr<Light> makeEnvironment(ObjectReader& j, const AssetResolver& assets,
                                       const Transform&) {
    if (j.has("file") == j.has("radiance"))
        j.fail("radiance",
               "an environment needs either \"radiance\" (constant) or \"file\" "
               "(a map), not both or neither");
    if (j.has("file")) return makeEnvironmentMap(j, assets);
    return std::make_unique<ConstantEnvironment>(j.colour("radiance"), readEnvSampling(j));
}

}  // namespace

std::unique_ptr<Light> makeLight(ObjectReader& json, const AssetResolver& assets,
                                 const Transform& worldToRender) {
    return buildByType(json, "light", lightTypes(), assets, worldToRender);
}

const LightTypes& lightTypes() {
    static const LightTypes table{
        {"point",
         {[](ObjectReader& j, const AssetResolver&, const Transform& place) {
              return std::make_unique<PointLight>(place.point(j.point("position")),
                                                  j.colour("intensity"));
          },
          &kPointKeys}},
        {"spot", {makeSpot, &kSpotKeys}},
        {"environment", {makeEnvironment, &kEnvironmentKeys}},
    };
    return table;
}

}  // namespace rr
