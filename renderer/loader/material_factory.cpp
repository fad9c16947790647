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

// Roughness bounds: a lobe of exponent 10^6 is ~0.1° wide, as sharp as any paper scene needs
// (the two-stage paper's sharpest is 1000); the bounds keep exponents and D far from float
// overflow (tests/test_microfacet_materials.cpp: SmallestAllowedRoughnessStillSamples).
const Range kRoughnessRange = Range::closed(1e-6, 1);  // exponent = 1/roughness ≤ 10^6
const Range kExponentRange = Range::closed(0, 1e6);
const Range kBeckmannRange = Range::closed(1e-4, 2);

KeySpec albedoKey() {
    return key("albedo").colourTexture(Range::unit()).byDefault(0.8).means("diffuse albedo");
}

KeySpec iorKey() {
    return key("ior")
        .number(Range::positive())
        .byDefault(1.5)
        .means("index of refraction, interior over exterior");
}

KeySpec reflectanceKey(const char* meaning) {
    return key("reflectance").colourTexture(Range::unit()).byDefault(1.0).means(meaning);
}

// A material name or an inline material object.
KeySpec materialReference(const char* name, const char* meaning) {
    return key(name)
        .custom("a material name or object",
                {{"anyOf", {{{"type", "string"}}, {{"$ref", "#/$defs/material"}}}}})
        .means(meaning);
}

const KeyTable kLambertKeys{"material/lambert", "ideal diffuse, f = albedo/π", {albedoKey()}};

const KeyTable kOrenNayarKeys{
    "material/oren_nayar",
    "rough diffuse, Oren & Nayar's 1994 qualitative model (σ = 0 is Lambert); cosine-weighted "
    "sampling",
    {albedoKey(), key("sigma")
                      .numberTexture(Range::closed(0, 90))
                      .byDefault(20.0)
                      .means("the facets' slope deviation σ in degrees")}};

const KeyTable kPhongKeys{
    "material/phong",
    "energy-normalised modified Phong (Lafortune & Willems 1994): f = diffuse/π + "
    "specular·(n + 2)/(2π)·cosⁿα; diffuse + specular ≤ 1 per channel when both are constants",
    {key("diffuse").colourTexture(Range::unit()).byDefault(0.0).means("diffuse albedo"),
     key("specular").colourTexture(Range::unit()).byDefault(0.5).means("specular albedo"),
     key("exponent").numberTexture(Range::nonNegative()).byDefault(32.0).means("n")}};

const KeyTable kLafortuneKeys{
    "material/lafortune",
    "generalised cosine lobes (Lafortune et al. 1997): f = diffuse/π + Σ albedo·max(0, "
    "cx·ux·vx + cy·uy·vy + cz·uz·vz)ⁿ; the directional albedo must not exceed 1 (checked)",
    {key("lobes")
         .custom("an array of 1 to 16 lobe objects",
                 {{"type", "array"},
                  {"items", {{"$ref", "#/$defs/lafortune_lobe"}}},
                  {"minItems", 1},
                  {"maxItems", 16}})
         .defaultSays("required unless `preset`")
         .means("the lobes (not with `preset`)"),
     key("preset").choice({"skin"}).optional().means(
         "pbrt-v1's measured skin (materials/skin.cpp): its diffuse and three lobes"),
     key("diffuse")
         .colourTexture(Range::unit())
         .defaultSays("0, or the preset's")
         .means("diffuse albedo")}};

const KeyTable kLafortuneLobeKeys{
    "lafortune_lobe",
    "one generalised cosine lobe",
    {key("c").numbers(3).means(
         "[cx, cy, cz]: [−1, −1, 1] a Phong lobe about the mirror direction, cx = cy > 0 "
         "retro-reflective, cx = cy = 0 peaks at the normal"),
     key("exponent").number(Range::nonNegative()).means("n"),
     key("albedo").colour().byDefault(1.0).means("scales the lobe (not normalised)")}};

const KeyTable kMixKeys{
    "material/mix",
    "f = w·fA + (1 − w)·fB; the `bsdf_lobe` decision picks A below w, rescaled for the child",
    {key("materials")
         .custom("[A, B]: two material names or objects",
                 {{"type", "array"},
                  {"items", {{"anyOf", {{{"type", "string"}}, {{"$ref", "#/$defs/material"}}}}}},
                  {"minItems", 2},
                  {"maxItems", 2}})
         .means("the two materials"),
     key("weight").numberTexture(Range::unit()).byDefault(0.5).means("the weight w of A")}};

const KeyTable kCheckerKeys{
    "material/checker",
    "the material of the square of the texture coordinates, as the `checker` texture",
    {materialReference("even", "the even squares' material"),
     materialReference("odd", "the odd squares' material"), squaresKey()}};

const KeyTable kMirrorKeys{
    "material/mirror",
    "perfect specular reflection",
    {key("reflectance").colour(Range::unit()).byDefault(1.0).means("reflected fraction")}};

const KeyTable kDielectricKeys{
    "material/dielectric",
    "smooth glass: a Fresnel-weighted choice (the `bsdf_lobe` decision) of specular reflection "
    "or refraction",
    {iorKey(), key("reflectance").colour(Range::unit()).byDefault(1.0).means("scales reflection"),
     key("transmittance").colour(Range::unit()).byDefault(1.0).means("scales refraction")}};

const KeyTable kBlinnKeys{
    "material/blinn",
    "Torrance–Sparrow microfacet reflection, Blinn–Phong D = (e+2)/(2π) cos^e θh, e = "
    "1/roughness; V-cavity shadowing; dielectric Fresnel; sampled by D·cos θh",
    {reflectanceKey("scales the Fresnel reflection"),
     key("roughness")
         .numberTexture(kRoughnessRange)
         .byDefault(0.1)
         .means("1/exponent (pbrt-v1's convention)"),
     iorKey()}};

const KeyTable kCookTorranceKeys{
    "material/cook_torrance",
    "microfacet reflection with the Beckmann distribution, Smith G1(wo)·G1(wi) (Walter et al. "
    "2007), dielectric Fresnel; sampled by Beckmann half vectors",
    {reflectanceKey("scales the Fresnel reflection"),
     key("roughness").numberTexture(kBeckmannRange).byDefault(0.2).means("Beckmann α"), iorKey()}};

KeySpec exponentPairKey(const char* name, Range range, const char* meaning) {
    return key(name)
        .numberTexture(range)
        .defaultSays("one pair required: roughness_u/_v or exponent_u/_v")
        .means(meaning);
}

const KeyTable kAshikhminShirleyKeys{
    "material/ashikhmin_shirley",
    "Ashikhmin & Shirley's anisotropic Phong BRDF (2000): a specular lobe with exponents n_u, "
    "n_v along the shading frame's u and v, Schlick Fresnel from Rs, and their diffuse term",
    {key("diffuse").colourTexture(Range::unit()).byDefault(0.5).means("Rd"),
     key("specular").colourTexture(Range::unit()).byDefault(0.5).means("Rs"),
     exponentPairKey("roughness_u", kRoughnessRange, "n_u = 1/roughness_u"),
     exponentPairKey("roughness_v", kRoughnessRange, "n_v = 1/roughness_v"),
     exponentPairKey("exponent_u", kExponentRange, "n_u"),
     exponentPairKey("exponent_v", kExponentRange, "n_v")}};

std::string formatRgb(const Rgb& c) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "[%.4g, %.4g, %.4g]", c.r, c.g, c.b);
    return buffer;
}

std::unique_ptr<Material> makeLambert(ObjectReader& j, const AssetResolver& assets,
                                      const MaterialReferences&) {
    return std::make_unique<Lambert>(readRgbTexture(j, "albedo", assets));
}

std::unique_ptr<Material> makeOrenNayar(ObjectReader& j, const AssetResolver& assets,
                                        const MaterialReferences&) {
    auto albedo = readRgbTexture(j, "albedo", assets);
    auto sigma = readFloatTexture(j, "sigma", assets);
    return std::make_unique<OrenNayar>(std::move(albedo), std::move(sigma));
}

std::unique_ptr<Material> makePhong(ObjectReader& j, const AssetResolver& assets,
                                    const MaterialReferences&) {
    auto diffuse = readRgbTexture(j, "diffuse", assets);
    auto specular = readRgbTexture(j, "specular", assets);
    auto exponent = readFloatTexture(j, "exponent", assets);
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
        ObjectReader lobe(array[i], pointer, kLafortuneLobeKeys);
        const auto c = lobe.numbers("c");
        const float exponent = lobe.real("exponent");
        const Rgb albedo = lobe.colour("albedo");
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
        j.choice("preset");
        if (j.has("lobes")) j.fail("lobes", "give either \"preset\" or \"lobes\", not both");
        lobes = Lafortune::skinLobes();
        defaultDiffuse = Lafortune::skinDiffuse();
    } else {
        lobes = readLafortuneLobes(j);
    }
    auto diffuse = readRgbTexture(j, "diffuse", defaultDiffuse, assets);
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
    auto weight = readFloatTexture(j, "weight", assets);
    return std::make_unique<MixMaterial>(a, b, std::move(weight));
}

std::unique_ptr<Material> makeChecker(ObjectReader& j, const AssetResolver&,
                                      const MaterialReferences& references) {
    const Material* even = references(j.raw("even"), j.pointerTo("even"));
    const Material* odd = references(j.raw("odd"), j.pointerTo("odd"));
    return std::make_unique<CheckerMaterial>(even, odd, readCheckerboard(j));
}

// Ashikhmin–Shirley's exponents: exactly one of the pairs roughness_u/roughness_v (n = 1/r)
// and exponent_u/exponent_v, each pair complete.
std::unique_ptr<Material> makeAshikhminShirley(ObjectReader& j, const AssetResolver& assets,
                                               const MaterialReferences&) {
    const TexturePtr<Rgb> diffuse = readRgbTexture(j, "diffuse", assets);
    const TexturePtr<Rgb> specular = readRgbTexture(j, "specular", assets);
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
    TexturePtr<float> tu = readFloatTexture(j, u, assets);
    TexturePtr<float> tv = readFloatTexture(j, v, assets);
    return std::make_unique<AshikhminShirley>(diffuse, specular, std::move(tu), std::move(tv),
                                              exponents);
}

std::unique_ptr<Material> makeBlinn(ObjectReader& j, const AssetResolver& assets,
                                    const MaterialReferences&) {
    auto r = readRgbTexture(j, "reflectance", assets);
    auto roughness = readFloatTexture(j, "roughness", assets);
    const float ior = j.real("ior");
    return std::make_unique<Blinn>(std::move(r), std::move(roughness), ior);
}

std::unique_ptr<Material> makeCookTorrance(ObjectReader& j, const AssetResolver& assets,
                                           const MaterialReferences&) {
    auto r = readRgbTexture(j, "reflectance", assets);
    auto alpha = readFloatTexture(j, "roughness", assets);
    const float ior = j.real("ior");
    return std::make_unique<CookTorrance>(std::move(r), std::move(alpha), ior);
}

}  // namespace

std::unique_ptr<Material> makeMaterial(ObjectReader& json, const AssetResolver& assets,
                                       const MaterialReferences& references) {
    return buildByType(json, "material", materialTypes(), assets, references);
}

const MaterialTypes& materialTypes() {
    static const MaterialTypes table{
        {"lambert", {makeLambert, &kLambertKeys}},
        {"oren_nayar", {makeOrenNayar, &kOrenNayarKeys}},
        {"phong", {makePhong, &kPhongKeys}},
        {"lafortune", {makeLafortune, &kLafortuneKeys}},
        {"mix", {makeMix, &kMixKeys}},
        {"checker", {makeChecker, &kCheckerKeys}},
        {"mirror",
         {[](ObjectReader& j, const AssetResolver&, const MaterialReferences&) {
              return std::make_unique<Mirror>(j.colour("reflectance"));
          },
          &kMirrorKeys}},
        {"dielectric",
         {[](ObjectReader& j, const AssetResolver&, const MaterialReferences&) {
              const float ior = j.real("ior");
              const Rgb r = j.colour("reflectance");
              const Rgb t = j.colour("transmittance");
              return std::make_unique<Dielectric>(ior, r, t);
          },
          &kDielectricKeys}},
        {"blinn", {makeBlinn, &kBlinnKeys}},
        {"cook_torrance", {makeCookTorrance, &kCookTorranceKeys}},
        {"ashikhmin_shirley", {makeAshikhminShirley, &kAshikhminShirleyKeys}},
    };
    return table;
}

std::vector<const KeyTable*> materialPartKeys() {
    return {&kLafortuneLobeKeys};
}

}  // namespace rr
