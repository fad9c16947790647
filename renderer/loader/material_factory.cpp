#include <cstdio>

#include "config/type_table.h"
#include "loader/factories.h"
#include "loader/texture_factory.h"
#include "scene/materials/ashikhmin_shirley.h"
#include "scene/materials/blinn.h"
#include "scene/materials/checker.h"
#include "scene/materials/cook_torrance.h"
#include "scene/materials/dielectric.h"
#include "scene/materials/lafortune.h"
#include "scene/materials/lambert.h"
#include "scene/materials/mirror.h"
#include "scene/materials/mix.h"
#include "scene/materials/oren_nayar.h"
#include "scene/materials/phong.h"

namespace rr {

namespace {

std::string formatRgb(const Rgb& c) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "[%.4g, %.4g, %.4g]", c.r, c.g, c.b);
    return buffer;
}

std::unique_ptr<Material> makeLambert(ObjectReader& j, const AssetResolver& assets,
                                      const MaterialReferences&) {
    return std::make_unique<Lambert>(readRgbTexture(j, "albedo", Rgb(0.8f), Range::unit(), assets));
}

std::unique_ptr<Material> makeOrenNayar(ObjectReader& j, const AssetResolver& assets,
                                        const MaterialReferences&) {
    auto albedo = readRgbTexture(j, "albedo", Rgb(0.8f), Range::unit(), assets);
    auto sigma = readFloatTexture(j, "sigma", 20.0f, Range::closed(0, 90), assets);
    return std::make_unique<OrenNayar>(std::move(albedo), std::move(sigma));
}

std::unique_ptr<Material> makePhong(ObjectReader& j, const AssetResolver& assets,
                                    const MaterialReferences&) {
    auto diffuse = readRgbTexture(j, "diffuse", Rgb(0.0f), Range::unit(), assets);
    auto specular = readRgbTexture(j, "specular", Rgb(0.5f), Range::unit(), assets);
    auto exponent = readFloatTexture(j, "exponent", 32.0f, Range::nonNegative(), assets);
    // Energy conservation (Lafortune & Willems 1994, §2): kd + ks ≤ 1 per channel.
    const Rgb* kd = constantValue(diffuse);
    const Rgb* ks = constantValue(specular);
    if (kd && ks && (*kd + *ks).maxComponent() > 1)
        j.fail("specular", "diffuse + specular = " + formatRgb(*kd + *ks) +
                               " exceeds 1: the material would reflect more than it receives");
    return std::make_unique<Phong>(std::move(diffuse), std::move(specular), std::move(exponent));
}

std::vector<LafortuneLobe> readLafortuneLobes(ObjectReader& j) {
    const Json& array = j.raw("lobes");
    if (!array.is_array() || array.empty() || array.size() > size_t(Lafortune::kMaxLobes))
        j.fail("lobes",
               "expected an array of 1 to " + std::to_string(Lafortune::kMaxLobes) + " lobes");
    std::vector<LafortuneLobe> lobes;
    for (size_t i = 0; i < array.size(); ++i) {
        const std::string pointer = j.pointerTo("lobes") + "/" + std::to_string(i);
        if (!array[i].is_object()) throw ConfigError(pointer, "expected a lobe object");
        ObjectReader lobe(array[i], pointer);
        const auto c = lobe.getNumbers("c", 3);
        const float exponent = lobe.getFloat("exponent", Range::nonNegative());
        const Rgb albedo = lobe.getRgb("albedo", Rgb(1.0f), Range::nonNegative());
        lobe.finish();
        lobes.push_back({Vec3(float(c[0]), float(c[1]), float(c[2])), exponent, albedo});
    }
    return lobes;
}

// The lobes are not normalised, so their albedos must be checked: over all outgoing
// directions the directional albedo (plus the diffuse albedo when it is a constant) must not
// exceed 1, up to the 10⁻³ accuracy of the lobe integrals' quadrature.
void checkLafortuneEnergy(ObjectReader& j, const Lafortune& m, const TexturePtr<Rgb>& diffuse,
                          const std::string& key) {
    Vec3 where;
    Rgb albedo = m.maxLobeAlbedo(&where);
    if (const Rgb* kd = constantValue(diffuse)) albedo += *kd;
    if (albedo.maxComponent() <= 1.001f) return;  // (false for NaN)
    char angle[64];
    std::snprintf(angle, sizeof angle, "θo = %.0f°", std::acos(where.z) * 180 / M_PI);
    j.fail(key, "the directional albedo reaches " + formatRgb(albedo) + " (near " + angle +
                    "), above 1: lower the lobe albedos" +
                    (constantValue(diffuse) ? " or the diffuse albedo" : ""));
}

std::unique_ptr<Material> makeLafortune(ObjectReader& j, const AssetResolver& assets,
                                        const MaterialReferences&) {
    std::vector<LafortuneLobe> lobes;
    Rgb defaultDiffuse(0.0f);
    const bool preset = j.has("preset");
    if (preset) {
        j.getChoice("preset", {"skin"});
        if (j.has("lobes")) j.fail("lobes", "give either \"preset\" or \"lobes\", not both");
        lobes = Lafortune::skinLobes();
        defaultDiffuse = Lafortune::skinDiffuse();
    } else {
        lobes = readLafortuneLobes(j);
    }
    auto diffuse = readRgbTexture(j, "diffuse", defaultDiffuse, Range::unit(), assets);
    auto material = std::make_unique<Lafortune>(diffuse, lobes);
    checkLafortuneEnergy(j, *material, diffuse, preset ? "preset" : "lobes");
    return material;
}

std::unique_ptr<Material> makeMix(ObjectReader& j, const AssetResolver& assets,
                                  const MaterialReferences& references) {
    const Json& children = j.raw("materials");
    if (!children.is_array() || children.size() != 2)
        j.fail("materials", "expected an array of two materials (names or objects)");
    const Material* a = references(children[0], j.pointerTo("materials") + "/0");
    const Material* b = references(children[1], j.pointerTo("materials") + "/1");
    auto weight = readFloatTexture(j, "weight", 0.5f, Range::unit(), assets);
    return std::make_unique<MixMaterial>(a, b, std::move(weight));
}

std::unique_ptr<Material> makeChecker(ObjectReader& j, const AssetResolver&,
                                      const MaterialReferences& references) {
    const Material* even = references(j.raw("even"), j.pointerTo("even"));
    const Material* odd = references(j.raw("odd"), j.pointerTo("odd"));
    return std::make_unique<CheckerMaterial>(even, odd, readCheckerboard(j));
}

// Roughness bounds: a lobe of exponent 10^6 is ~0.1° wide, as sharp as any paper scene needs
// (the two-stage paper's sharpest is 1000); the bounds keep exponents and D far from float
// overflow (tests/test_microfacet_materials.cpp: SmallestAllowedRoughnessStillSamples).
const Range kRoughnessRange = Range::closed(1e-6, 1);  // exponent = 1/roughness ≤ 10^6
const Range kExponentRange = Range::closed(0, 1e6);
const Range kBeckmannRange = Range::closed(1e-4, 2);

// Ashikhmin–Shirley's exponents: exactly one of the pairs roughness_u/roughness_v (n = 1/r)
// and exponent_u/exponent_v, each pair complete.
std::unique_ptr<Material> makeAshikhminShirley(ObjectReader& j, const AssetResolver& assets,
                                               const MaterialReferences&) {
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
    const Range range = exponents ? kExponentRange : kRoughnessRange;
    TexturePtr<float> tu = readFloatTexture(j, u, 1.0f, range, assets);
    TexturePtr<float> tv = readFloatTexture(j, v, 1.0f, range, assets);
    return std::make_unique<AshikhminShirley>(diffuse, specular, std::move(tu), std::move(tv),
                                              exponents);
}

std::unique_ptr<Material> makeBlinn(ObjectReader& j, const AssetResolver& assets,
                                    const MaterialReferences&) {
    auto r = readRgbTexture(j, "reflectance", Rgb(1.0f), Range::unit(), assets);
    auto roughness = readFloatTexture(j, "roughness", 0.1f, kRoughnessRange, assets);
    const float ior = j.getFloat("ior", 1.5f, Range::positive());
    return std::make_unique<Blinn>(std::move(r), std::move(roughness), ior);
}

std::unique_ptr<Material> makeCookTorrance(ObjectReader& j, const AssetResolver& assets,
                                           const MaterialReferences&) {
    auto r = readRgbTexture(j, "reflectance", Rgb(1.0f), Range::unit(), assets);
    auto alpha = readFloatTexture(j, "roughness", 0.2f, kBeckmannRange, assets);
    const float ior = j.getFloat("ior", 1.5f, Range::positive());
    return std::make_unique<CookTorrance>(std::move(r), std::move(alpha), ior);
}

}  // namespace

std::unique_ptr<Material> makeMaterial(ObjectReader& json, const AssetResolver& assets,
                                       const MaterialReferences& references) {
    static const TypeTable<Material, const AssetResolver&, const MaterialReferences&> table{
        {"lambert", makeLambert},
        {"oren_nayar", makeOrenNayar},
        {"phong", makePhong},
        {"lafortune", makeLafortune},
        {"mix", makeMix},
        {"checker", makeChecker},
        {"mirror",
         [](ObjectReader& j, const AssetResolver&, const MaterialReferences&) {
             return std::make_unique<Mirror>(j.getRgb("reflectance", Rgb(1.0f), Range::unit()));
         }},
        {"dielectric",
         [](ObjectReader& j, const AssetResolver&, const MaterialReferences&) {
             const float ior = j.getFloat("ior", 1.5f, Range::positive());
             const Rgb r = j.getRgb("reflectance", Rgb(1.0f), Range::unit());
             const Rgb t = j.getRgb("transmittance", Rgb(1.0f), Range::unit());
             return std::make_unique<Dielectric>(ior, r, t);
         }},
        {"blinn", makeBlinn},
        {"cook_torrance", makeCookTorrance},
        {"ashikhmin_shirley", makeAshikhminShirley},
    };
    return buildByType(json, "material", table, assets, references);
}

}  // namespace rr
