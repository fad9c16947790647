#include "techniques/tais/tais_integrator.h"

#include <algorithm>

#include "config/config_error.h"
#include "config/json_reader.h"
#include "render/scan_bands.h"
#include "scene/scene_features.h"
#include "techniques/tais/map_guide.h"
#include "techniques/tais/tais_pixels.h"

namespace rr::tais {

namespace {

std::string mapList(const TaisSettings& s) {
    std::string list;
    for (int k = 0; k < kMapKinds; ++k)
        if (s.enabled[k]) list += (list.empty() ? "" : ", ") + std::string(mapName(MapKind(k)));
    return list.empty() ? "none" : list;
}

}  // namespace

TaisIntegrator::TaisIntegrator(const TaisSettings& settings,
                               std::array<std::string, kMapKinds> mapPointers)
    : settings_(settings), mapPointers_(std::move(mapPointers)) {}

nlohmann::json TaisIntegrator::parameters() const {
    nlohmann::json p = readParameters();
    p["maps_used"] = mapList(settings_);
    settings_.path.addTo(&p);
    return p;
}

namespace {

// Next-event estimation happens at surfaces with a diffuse or glossy lobe and in media.
bool samplesLights(const Scene& scene) {
    for (const auto& m : scene.materials())
        if (m->hasNonSpecular()) return true;
    return scene.hasMedia();
}

// The scatter-direction map steers surfaces whose material has no specular lobe.
bool hasNonSpecularOnlySurfaces(const Scene& scene) {
    for (const auto& m : scene.materials())
        if (m->hasNonSpecular() && !(m->lobes() & kSpecular)) return true;
    return false;
}

}  // namespace

bool sceneHasDecision(const Scene& scene, MapKind kind) {
    const SceneFeatures f = sceneFeatures(scene);
    switch (kind) {
        case MapKind::Time:
            return f.motionBlur;
        case MapKind::Lens:
            return f.thinLens;
        case MapKind::ScatterDistance:
            return f.media;
        case MapKind::Bifurcation:
            return f.bifurcation;
        case MapKind::LightSelection:
            return scene.lights().size() > 1 && samplesLights(scene);
        case MapKind::PointOnLight:
            for (const Light* light : scene.lights())
                if (invertibleLight(*light)) return samplesLights(scene);
            return false;
        case MapKind::ScatterDirection:
            return hasNonSpecularOnlySurfaces(scene);
        case MapKind::Count:
            break;
    }
    return false;
}

void TaisIntegrator::prepare(const Scene& scene) {
    for (int k = 0; k < kMapKinds; ++k) {
        const MapKind kind = MapKind(k);
        const bool has = sceneHasDecision(scene, kind);
        if (settings_.automatic) {
            settings_.enabled[k] = has;
        } else if (settings_.enabled[k] && !has) {
            throw ConfigError(mapPointers_[k], "the scene has no decision for the " +
                                                   std::string(mapName(kind)) +
                                                   " map (see \"auto\")");
        }
    }
    invertible_.clear();
    for (const Light* light : scene.lights())
        invertible_.push_back(invertibleLight(*light));
}

std::unique_ptr<RenderSchedule> TaisIntegrator::schedule(const ScheduleInputs& in) const {
    const Scene& scene = in.scene;
    return std::make_unique<ScanBands>(
        in.width, in.height, in.spp, settings_.bandRows, settings_.bandWarmupRows,
        [&scene, this](const Sampler& sampler) {
            return std::make_unique<TaisPixels>(scene, *this, sampler);
        });
}

namespace {

const TaisSettings kDefaults;

KeySpec sizeKey(const char* name, int fallback, int lo, int hi, const char* meaning) {
    return key(name).integer(Range::closed(lo, hi)).byDefault(fallback).means(meaning);
}

const KeyTable kTaisKeys{
    "integrator/tais",
    "`path_mis` with table-driven adaptive importance sampling (Cline, Adams & Egbert 2008): "
    "per-pixel importance maps learned from the pixels rendered before steer the path's "
    "decisions; unbiased (the contribution filter aside); a fixed spp in scan order",
    {key("maps")
         .custom(R"(`"auto"` or an array of map names)",
                 {{"anyOf",
                   {{{"const", "auto"}},
                    {{"type", "array"},
                     {"uniqueItems", true},
                     {"items",
                      {{"enum",
                        {"time", "lens", "scatter_distance", "bifurcation", "light_selection",
                         "point_on_light", "scatter_direction"}}}}}}}})
         .byDefault("auto")
         .means("the maps of the paper's Table 1; `\"auto\"`: those whose decision the scene "
                "has; `[]` is `path_mis`, bit for bit"),
     key("alpha")
         .number(Range::open(0, 1))
         .byDefault(kDefaults.alpha)
         .means("eq. (2): the probability that a world-space map makes its decision"),
     key("alpha_follows_evidence")
         .boolean()
         .byDefault(kDefaults.alphaFollowsEvidence)
         .means("beyond the paper: a world map mixes in only its credited part, with alpha × "
                "that part's share of the decision's mass; false: eq. (2)"),
     sizeKey("time_cells", kDefaults.timeCells, 2, 4096, "1-D time map size"),
     sizeKey("scatter_distance_cells", kDefaults.scatterDistanceCells, 2, 4096,
             "1-D scatter-distance map size"),
     sizeKey("lens_size", kDefaults.lensSize, 2, 256, "the lens map is size × size"),
     sizeKey("point_on_light_size", kDefaults.pointOnLightSize, 2, 256,
             "the point-on-light map is size × size"),
     sizeKey("scatter_direction_size", kDefaults.scatterDirectionSize, 2, 256,
             "the scatter-direction map is size × size"),
     sizeKey("scatter_direction_bounces", kDefaults.scatterDirectionBounces, 1, 2,
             "2 adds a map for the second non-specular bounce (fig. 14)"),
     sizeKey("bifurcation_vertices", kDefaults.bifurcationVertices, 1,
             MapGuide::kMaxBifurcationVertices,
             "path vertices with their own reflect/transmit entries"),
     sizeKey("light_selection_vertices", kDefaults.lightSelectionVertices, 1,
             MapGuide::kMaxLightSelectionVertices,
             "beyond the paper: path vertices whose light choice has its own entries"),
     key("credit")
         .choice({"downstream", "path"})
         .byDefault("downstream")
         .means("what a sample adds to a map: the paper's |L(x)| (`path`), or the part of "
                "L(x) gathered after the decision"),
     key("contribution_filter")
         .boolean()
         .byDefault(kDefaults.contributionFilter)
         .means("eq. (4): clamp each pixel's samples; biased, so report it apart"),
     sizeKey("band_rows", kDefaults.bandRows, 1, 1 << 20,
             "rows per band, scanned independently from uniform maps (the image depends on "
             "it, never on the thread count)"),
     sizeKey("band_warmup_rows", kDefaults.bandWarmupRows, 0, 1 << 20,
             "rows of the band above scanned first to learn the maps, their samples "
             "discarded")}};

std::unique_ptr<TaisIntegrator> makeTaisIntegrator(ObjectReader& j, const PathSettings& path) {
    TaisSettings s;
    s.path = path;
    std::array<std::string, kMapKinds> pointers;
    const Json* given = j.rawOptional("maps");
    const Json& maps = given ? *given : j.spec("maps").fallback;
    if (maps.is_string() && maps.get<std::string>() == "auto") {
        s.automatic = true;
    } else if (maps.is_array()) {
        s.automatic = false;
        for (size_t i = 0; i < maps.size(); ++i) {
            const std::string pointer = j.pointerTo("maps") + "/" + std::to_string(i);
            MapKind kind;
            if (!maps[i].is_string() || !parseMapName(maps[i].get<std::string>(), &kind))
                throw ConfigError(pointer,
                                  "expected a map name: time, lens, scatter_distance, "
                                  "bifurcation, light_selection, point_on_light or "
                                  "scatter_direction");
            if (s.uses(kind)) throw ConfigError(pointer, "map listed twice");
            s.enabled[static_cast<int>(kind)] = true;
            pointers[static_cast<int>(kind)] = pointer;
        }
    } else {
        j.fail("maps", "expected \"auto\" or an array of map names");
    }
    s.alpha = j.real("alpha");
    s.alphaFollowsEvidence = j.boolean("alpha_follows_evidence");
    auto size = [&](const char* key) { return static_cast<int>(j.integer(key)); };
    s.timeCells = size("time_cells");
    s.scatterDistanceCells = size("scatter_distance_cells");
    s.lensSize = size("lens_size");
    s.pointOnLightSize = size("point_on_light_size");
    s.scatterDirectionSize = size("scatter_direction_size");
    s.scatterDirectionBounces = size("scatter_direction_bounces");
    s.bifurcationVertices = size("bifurcation_vertices");
    s.lightSelectionVertices = size("light_selection_vertices");
    s.credit = j.choice("credit") == "path" ? Credit::Path : Credit::Downstream;
    s.contributionFilter = j.boolean("contribution_filter");
    s.bandRows = size("band_rows");
    s.bandWarmupRows = size("band_warmup_rows");
    return std::make_unique<TaisIntegrator>(s, std::move(pointers));
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addIntegrator(
        "tais", kTaisKeys,
        [](ObjectReader& json, const IntegratorContext& context) {
            std::unique_ptr<TaisIntegrator> tais = makeTaisIntegrator(json, context.path);
            const TaisIntegrator* integrator = tais.get();
            return BuiltIntegrator{std::move(tais), [integrator](const ScheduleInputs& in) {
                                       return integrator->schedule(in);
                                   }};
        },
        /*rendersMedia=*/true);
}

}  // namespace rr::tais
