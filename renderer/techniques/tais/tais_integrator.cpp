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
    static const char* credits[] = {"path", "downstream"};
    nlohmann::json p = {{"type", name()},
                        {"maps", settings_.automatic ? "auto" : "listed"},
                        {"maps_used", mapList(settings_)},
                        {"alpha", settings_.alpha},
                        {"alpha_follows_evidence", settings_.alphaFollowsEvidence},
                        {"time_cells", settings_.timeCells},
                        {"scatter_distance_cells", settings_.scatterDistanceCells},
                        {"lens_size", settings_.lensSize},
                        {"point_on_light_size", settings_.pointOnLightSize},
                        {"scatter_direction_size", settings_.scatterDirectionSize},
                        {"scatter_direction_bounces", settings_.scatterDirectionBounces},
                        {"bifurcation_vertices", settings_.bifurcationVertices},
                        {"light_selection_vertices", settings_.lightSelectionVertices},
                        {"credit", credits[static_cast<int>(settings_.credit)]},
                        {"contribution_filter", settings_.contributionFilter},
                        {"band_rows", settings_.bandRows},
                        {"band_warmup_rows", settings_.bandWarmupRows}};
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

std::unique_ptr<TaisIntegrator> makeTaisIntegrator(ObjectReader& j, const PathSettings& path) {
    TaisSettings s;
    s.path = path;
    std::array<std::string, kMapKinds> pointers;
    if (const Json* maps = j.rawOptional("maps")) {
        if (maps->is_string() && maps->get<std::string>() == "auto") {
            s.automatic = true;
        } else if (maps->is_array()) {
            s.automatic = false;
            for (size_t i = 0; i < maps->size(); ++i) {
                const std::string pointer = j.pointerTo("maps") + "/" + std::to_string(i);
                MapKind kind;
                if (!(*maps)[i].is_string() || !parseMapName((*maps)[i].get<std::string>(), &kind))
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
    }
    s.alpha = j.getFloat("alpha", s.alpha, Range::open(0, 1));
    s.alphaFollowsEvidence = j.getBool("alpha_follows_evidence", s.alphaFollowsEvidence);
    auto size = [&](const char* key, int fallback, int lo, int hi) {
        return static_cast<int>(j.getInt(key, fallback, Range::closed(lo, hi)));
    };
    s.timeCells = size("time_cells", s.timeCells, 2, 4096);
    s.scatterDistanceCells = size("scatter_distance_cells", s.scatterDistanceCells, 2, 4096);
    s.lensSize = size("lens_size", s.lensSize, 2, 256);
    s.pointOnLightSize = size("point_on_light_size", s.pointOnLightSize, 2, 256);
    s.scatterDirectionSize = size("scatter_direction_size", s.scatterDirectionSize, 2, 256);
    s.scatterDirectionBounces = size("scatter_direction_bounces", s.scatterDirectionBounces, 1, 2);
    s.bifurcationVertices =
        size("bifurcation_vertices", s.bifurcationVertices, 1, MapGuide::kMaxBifurcationVertices);
    s.lightSelectionVertices = size("light_selection_vertices", s.lightSelectionVertices, 1,
                                    MapGuide::kMaxLightSelectionVertices);
    s.credit = j.getChoice("credit", {"downstream", "path"}, "downstream") == "path"
                   ? Credit::Path
                   : Credit::Downstream;
    s.contributionFilter = j.getBool("contribution_filter", false);
    s.bandRows = size("band_rows", s.bandRows, 1, 1 << 20);
    s.bandWarmupRows = size("band_warmup_rows", s.bandWarmupRows, 0, 1 << 20);
    return std::make_unique<TaisIntegrator>(s, std::move(pointers));
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addIntegrator(
        "tais",
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
