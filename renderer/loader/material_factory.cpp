#include <cstdio>

#include "loader/factories.h"
#include "loader/texture_factory.h"
#include "loader/type_table.h"
#include "scene/materials/checker.h"
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
    };
    return buildByType(json, "material", table, assets, references);
}

}  // namespace rr
