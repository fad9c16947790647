#include "loader/render_settings_reader.h"

#include <cmath>
#include <string>

#include "config/type_table.h"
#include "render/renderer.h"

namespace rr {

namespace {

constexpr double kMaxPixels = 67108864.0;  // 2^26

const RenderSettings kDefaults;
const PathSettings kPathDefaults;
const FilterSettings kFilterDefaults;

const KeyTable kRenderKeys{
    "render",
    "image size, samples, seed, sampler, reconstruction filter, path length, light selection",
    {key("resolution")
         .numbers(2, Range::closed(1, 16384))
         .byDefault({kDefaults.width, kDefaults.height})
         .means("image size in pixels [w, h], integers, w·h ≤ 2²⁶"),
     key("spp")
         .integer(Range::closed(1, kMaxSpp))
         .byDefault(kDefaults.spp)
         .estimandNeutral()
         .means("samples per pixel (× the integrator's draws per sample ≤ 2²⁴); also the "
                "number of samples the structured samplers stratify together"),
     key("seed")
         .integer(Range::closed(0, 4294967295.0))
         .byDefault(kDefaults.seed)
         .estimandNeutral()
         .means("random seed; the image is a pure function of scene, seed and spp"),
     key("sampler")
         .choice({"independent", "stratified", "hammersley", "pbrt_v1"})
         .byDefault("independent")
         .estimandNeutral()
         .means("how sample coordinates are drawn (see Sampling)"),
     key("filter")
         .custom("`\"box\"`, `\"mitchell\"`, `\"gaussian\"`, or a filter object",
                 {{"anyOf",
                   {{{"enum", {"box", "mitchell", "gaussian"}}}, {{"$ref", "#/$defs/filter"}}}}})
         .byDefault("box")
         .means("the reconstruction filter (below); part of the image's expectation: a "
                "reference must use the same filter"),
     key("max_depth")
         .integer(Range::closed(-1, 100000))
         .byDefault(kPathDefaults.maxDepth)
         .means("maximum scattering events on a path, on surfaces or in media (1: direct "
                "lighting); −1: no limit but Russian roulette (capped at 1000)"),
     key("rr_depth")
         .integer(Range::closed(1, 100000))
         .byDefault(kPathDefaults.rrDepth)
         .estimandNeutral()
         .means("Russian roulette starts after this many scattering events"),
     key("rr_survival")
         .number(Range{0, 1, true, false})
         .optional()
         .estimandNeutral()
         .means("a fixed survival probability for Russian roulette (pbrt-v1's path "
                "integrator: 0.5) instead of the throughput-driven one"),
     key("rr_threshold")
         .number(Range{0, 1, true, false})
         .byDefault(kPathDefaults.rrThreshold)
         .estimandNeutral()
         .means("play the throughput-driven roulette only where its survival probability is "
                "below this (not with rr_survival); see results/tables/rr_efficiency.md"),
     key("light_selection")
         .choice({"power", "uniform"})
         .byDefault("power")
         .estimandNeutral()
         .means("how next-event estimation picks a light: ∝ emitted power, or uniformly")}};

const KeyTable kBoxKeys{"filter/box", "1 on the pixel's own square (nothing is splatted)", {}};

KeySpec radiusKey() {
    return key("radius")
        .number(Range::closed(0.5, ReconstructionFilter::kMaxRadius))
        .byDefault(kFilterDefaults.radius)
        .means("half-width in pixels");
}

const KeyTable kMitchellKeys{
    "filter/mitchell",
    "Mitchell & Netravali's cubic at 2|d|/r, times 2/r; negative lobes beyond r/2",
    {radiusKey(),
     key("b").number(Range::unit()).byDefault(kFilterDefaults.b).means("the cubic's B"),
     key("c").number(Range::unit()).byDefault(kFilterDefaults.c).means("the cubic's C")}};

const KeyTable kGaussianKeys{
    "filter/gaussian",
    "exp(−α d²) − exp(−α r²) on |d| < r, over its integral (pbrt-v1's gaussian)",
    {radiusKey(), key("alpha")
                      .number(Range::closed(0.01, 100))
                      .byDefault(kFilterDefaults.alpha)
                      .means("the falloff α")}};

const std::vector<std::pair<FilterType, const KeyTable*>> kFilterTypes{
    {FilterType::Box, &kBoxKeys},
    {FilterType::Mitchell, &kMitchellKeys},
    {FilterType::Gaussian, &kGaussianKeys}};

// "filter": "box", "mitchell" or "gaussian" (with their default parameters), or an object
// {"type": ..., and the type's parameters}.
FilterSettings readFilter(ObjectReader& render) {
    const Json* value = render.rawOptional("filter");
    FilterSettings f;
    if (!value) return f;
    const std::string pointer = render.pointerTo("filter");
    auto typeOf = [&](const std::string& name, const std::string& at) {
        for (const auto& [type, keys] : kFilterTypes)
            if (name == filterName(type)) return type;
        throw ConfigError(at, "unknown filter type \"" + name +
                                  "\", expected one of: \"box\", \"mitchell\", \"gaussian\"");
    };
    if (value->is_string()) {
        f.type = typeOf(value->get<std::string>(), pointer);
        return f;
    }
    if (!value->is_object())
        throw ConfigError(pointer, "expected a filter name or an object with a \"type\"");
    ObjectReader j(*value, pointer, typeKeyTable());
    f.type = typeOf(j.string("type"), j.pointerTo("type"));
    for (const auto& [type, keys] : kFilterTypes)
        if (type == f.type) j.addKeys(*keys);
    if (f.type != FilterType::Box) f.radius = j.number("radius");
    if (f.type == FilterType::Mitchell) {
        f.b = j.number("b");
        f.c = j.number("c");
    }
    if (f.type == FilterType::Gaussian) f.alpha = j.number("alpha");
    j.finish();
    return f;
}

}  // namespace

const KeyTable& renderKeys() {
    return kRenderKeys;
}

std::vector<std::pair<std::string, const KeyTable*>> filterTypeKeys() {
    std::vector<std::pair<std::string, const KeyTable*>> types;
    for (const auto& [type, keys] : kFilterTypes)
        types.emplace_back(filterName(type), keys);
    return types;
}

RenderSettings readRenderSettings(ObjectReader& j, PathSettings* path) {
    j.addKeys(kRenderKeys);
    RenderSettings r;
    const auto res = j.numbers("resolution");
    if (res[0] != std::floor(res[0]) || res[1] != std::floor(res[1]))
        j.fail("resolution", "expected two integers");
    // The film holds several floats per pixel and the EXR a copy: 2^26 pixels (e.g.
    // 8192 × 8192) keep both within a few GB.
    if (res[0] * res[1] > kMaxPixels)
        j.fail("resolution",
               "width × height = " + std::to_string(int64_t(res[0] * res[1])) +
                   " pixels exceeds the limit of 2^26 = " + std::to_string(int64_t(kMaxPixels)));
    r.width = static_cast<int>(res[0]);
    r.height = static_cast<int>(res[1]);
    r.spp = static_cast<uint32_t>(j.integer("spp"));
    r.seed = static_cast<uint32_t>(j.integer("seed"));
    parseSamplerType(j.choice("sampler"), &r.sampler);
    r.filter = readFilter(j);
    path->maxDepth = static_cast<int>(j.integer("max_depth"));
    path->rrDepth = static_cast<int>(j.integer("rr_depth"));
    if (j.has("rr_survival")) {
        path->rrSurvival = j.real("rr_survival");
        // A positive double that rounds to 0 in float would silently mean "no fixed survival".
        if (!(path->rrSurvival > 0)) j.fail("rr_survival", "too small to be a probability");
    }
    if (j.has("rr_threshold")) {
        path->rrThreshold = j.real("rr_threshold");
        if (!(path->rrThreshold > 0)) j.fail("rr_threshold", "too small to be a probability");
        if (path->rrSurvival > 0)
            j.fail("rr_threshold",
                   "applies to the throughput-driven survival probability; "
                   "rr_survival fixes it instead");
    }
    r.lightSelection =
        j.choice("light_selection") == "uniform" ? LightSelection::Uniform : LightSelection::Power;
    j.finish();
    return r;
}

}  // namespace rr
