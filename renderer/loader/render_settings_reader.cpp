#include "loader/render_settings_reader.h"

#include <cmath>
#include <string>

#include "render/renderer.h"

namespace rr {

namespace {

constexpr double kMaxPixels = 67108864.0;  // 2^26

// "filter": "box", "mitchell" or "gaussian" (with their default parameters), or an object
// {"type": ..., and the type's parameters}.
FilterSettings readFilter(ObjectReader& render) {
    const Json* value = render.rawOptional("filter");
    FilterSettings f;
    if (!value) return f;
    const std::string pointer = render.pointerTo("filter");
    auto typeOf = [&](const std::string& name, const std::string& at) {
        for (FilterType t : {FilterType::Box, FilterType::Mitchell, FilterType::Gaussian})
            if (name == filterName(t)) return t;
        throw ConfigError(at, "unknown filter type \"" + name +
                                  "\", expected one of: \"box\", \"mitchell\", \"gaussian\"");
    };
    if (value->is_string()) {
        f.type = typeOf(value->get<std::string>(), pointer);
        return f;
    }
    if (!value->is_object())
        throw ConfigError(pointer, "expected a filter name or an object with a \"type\"");
    ObjectReader j(*value, pointer);
    f.type = typeOf(j.getString("type"), j.pointerTo("type"));
    if (f.type != FilterType::Box)
        f.radius =
            j.getNumber("radius", f.radius, Range::closed(0.5, ReconstructionFilter::kMaxRadius));
    if (f.type == FilterType::Mitchell) {
        f.b = j.getNumber("b", f.b, Range::closed(0, 1));
        f.c = j.getNumber("c", f.c, Range::closed(0, 1));
    }
    if (f.type == FilterType::Gaussian)
        f.alpha = j.getNumber("alpha", f.alpha, Range::closed(0.01, 100));
    j.finish();
    return f;
}

}  // namespace

RenderSettings readRenderSettings(ObjectReader& j, PathSettings* path) {
    RenderSettings r;
    if (j.has("resolution")) {
        const auto res = j.getNumbers("resolution", 2, Range::closed(1, 16384));
        if (res[0] != std::floor(res[0]) || res[1] != std::floor(res[1]))
            j.fail("resolution", "expected two integers");
        // The film holds several floats per pixel and the EXR a copy: 2^26 pixels (e.g.
        // 8192 × 8192) keep both within a few GB.
        if (res[0] * res[1] > kMaxPixels)
            j.fail("resolution", "width × height = " + std::to_string(int64_t(res[0] * res[1])) +
                                     " pixels exceeds the limit of 2^26 = " +
                                     std::to_string(int64_t(kMaxPixels)));
        r.width = static_cast<int>(res[0]);
        r.height = static_cast<int>(res[1]);
    }
    r.spp = static_cast<uint32_t>(j.getInt("spp", 16, Range::closed(1, kMaxSpp)));
    r.seed = static_cast<uint32_t>(j.getInt("seed", 0, Range::closed(0, 4294967295.0)));
    const std::string sampler = j.getChoice(
        "sampler", {"independent", "stratified", "hammersley", "pbrt_v1"}, "independent");
    parseSamplerType(sampler, &r.sampler);
    r.filter = readFilter(j);
    const PathSettings defaults;
    path->maxDepth =
        static_cast<int>(j.getInt("max_depth", defaults.maxDepth, Range::closed(-1, 100000)));
    path->rrDepth =
        static_cast<int>(j.getInt("rr_depth", defaults.rrDepth, Range::closed(1, 100000)));
    if (j.has("rr_survival")) {
        path->rrSurvival = static_cast<float>(j.getNumber("rr_survival", Range{0, 1, true, false}));
        // A positive double that rounds to 0 in float would silently mean "no fixed survival".
        if (!(path->rrSurvival > 0)) j.fail("rr_survival", "too small to be a probability");
    }
    if (j.has("rr_threshold")) {
        path->rrThreshold =
            static_cast<float>(j.getNumber("rr_threshold", Range{0, 1, true, false}));
        if (!(path->rrThreshold > 0)) j.fail("rr_threshold", "too small to be a probability");
        if (path->rrSurvival > 0)
            j.fail("rr_threshold",
                   "applies to the throughput-driven survival probability; "
                   "rr_survival fixes it instead");
    }
    r.lightSelection = j.getChoice("light_selection", {"power", "uniform"}, "power") == "uniform"
                           ? LightSelection::Uniform
                           : LightSelection::Power;
    j.finish();
    return r;
}

}  // namespace rr
