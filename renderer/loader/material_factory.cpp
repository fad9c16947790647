#include "loader/factories.h"
#include "loader/texture_factory.h"
#include "loader/type_table.h"
#include "scene/materials/ashikhmin_shirley.h"
#include "scene/materials/blinn.h"
#include "scene/materials/cook_torrance.h"
#include "scene/materials/dielectric.h"
#include "scene/materials/lambert.h"
#include "scene/materials/mirror.h"

namespace rr {

namespace {

// Ashikhmin–Shirley's exponents: exactly one of the pairs roughness_u/roughness_v (n = 1/r)
// and exponent_u/exponent_v, each pair complete.
std::unique_ptr<Material> makeAshikhminShirley(ObjectReader& j, const AssetResolver& assets) {
    const TexturePtr<Rgb> diffuse = readRgbTexture(j, "diffuse", Rgb(0.5f), Range::unit(), assets);
    const TexturePtr<Rgb> specular =
        readRgbTexture(j, "specular", Rgb(0.5f), Range::unit(), assets);
    const bool roughness = j.has("roughness_u") || j.has("roughness_v");
    const bool exponents = j.has("exponent_u") || j.has("exponent_v");
    if (roughness && exponents)
        j.fail(j.has("exponent_u") ? "exponent_u" : "exponent_v",
               "give either roughness_u/roughness_v or exponent_u/exponent_v, not both");
    if (!roughness && !exponents)
        j.fail("roughness_u", "missing: give roughness_u/roughness_v or exponent_u/exponent_v");
    const std::string u = exponents ? "exponent_u" : "roughness_u";
    const std::string v = exponents ? "exponent_v" : "roughness_v";
    for (const std::string& key : {u, v})
        if (!j.has(key)) j.fail(key, "missing: the pair needs both its u and v values");
    const Range range = exponents ? Range::nonNegative() : Range{0, 1, true, false};
    TexturePtr<float> tu = readFloatTexture(j, u, 1.0f, range, assets);
    TexturePtr<float> tv = readFloatTexture(j, v, 1.0f, range, assets);
    return std::make_unique<AshikhminShirley>(diffuse, specular, std::move(tu), std::move(tv),
                                              exponents);
}

}  // namespace

std::unique_ptr<Material> makeMaterial(ObjectReader& json, const AssetResolver& assets) {
    static const TypeTable<Material, const AssetResolver&> table{
        {"lambert",
         [](ObjectReader& j, const AssetResolver&) {
             return std::make_unique<Lambert>(j.getRgb("albedo", Rgb(0.8f), Range::unit()));
         }},
        {"mirror",
         [](ObjectReader& j, const AssetResolver&) {
             return std::make_unique<Mirror>(j.getRgb("reflectance", Rgb(1.0f), Range::unit()));
         }},
        {"dielectric",
         [](ObjectReader& j, const AssetResolver&) {
             const float ior = j.getFloat("ior", 1.5f, Range::positive());
             const Rgb r = j.getRgb("reflectance", Rgb(1.0f), Range::unit());
             const Rgb t = j.getRgb("transmittance", Rgb(1.0f), Range::unit());
             return std::make_unique<Dielectric>(ior, r, t);
         }},
        {"blinn",
         [](ObjectReader& j, const AssetResolver& resolver) {
             auto r = readRgbTexture(j, "reflectance", Rgb(1.0f), Range::unit(), resolver);
             auto roughness = readFloatTexture(j, "roughness", 0.1f, {0, 1, true, false}, resolver);
             const float ior = j.getFloat("ior", 1.5f, Range::positive());
             return std::make_unique<Blinn>(std::move(r), std::move(roughness), ior);
         }},
        {"cook_torrance",
         [](ObjectReader& j, const AssetResolver& resolver) {
             auto r = readRgbTexture(j, "reflectance", Rgb(1.0f), Range::unit(), resolver);
             auto alpha = readFloatTexture(j, "roughness", 0.2f, {0, 2, true, false}, resolver);
             const float ior = j.getFloat("ior", 1.5f, Range::positive());
             return std::make_unique<CookTorrance>(std::move(r), std::move(alpha), ior);
         }},
        {"ashikhmin_shirley", makeAshikhminShirley},
    };
    return buildByType(json, "material", table, assets);
}

}  // namespace rr
