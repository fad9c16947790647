#include "loader/scene_loader.h"

#include <chrono>
#include <optional>
#include <string>

#include "config/type_table.h"
#include "loader/camera_reader.h"
#include "loader/factories.h"
#include "loader/material_catalog.h"
#include "loader/scene_keys.h"
#include "loader/shape_reader.h"
#include "render/renderer.h"

namespace rr {

namespace {

// The structured samplers index a pixel's spp × repeats draws of one decision in 32 bits, and
// the float sample count is exact to kMaxSpp: the product is bounded by it too.
void checkStructuredSampleCount(const RenderSettings& render, const Integrator& integrator,
                                const std::string& sppPointer) {
    const uint64_t repeats = integrator.decisionRepeats();
    const uint64_t product = uint64_t(render.spp) * repeats;
    if (product > kMaxSpp)
        throw ConfigError(
            sppPointer,
            "spp (" + std::to_string(render.spp) + ") × the " + std::to_string(repeats) +
                " draws per sample of the integrator's decisions = " + std::to_string(product) +
                " exceeds 2^24 = " + std::to_string(kMaxSpp));
}

// Where the first medium is declared (the scene's, else the first shape's interior), for the
// error if the integrator cannot render media.
std::string firstMediumPointer(const Json& document) {
    if (document.contains("medium")) return "/medium";
    const auto shapes = document.find("shapes");
    if (shapes == document.end() || !shapes->is_array()) return "";
    for (size_t i = 0; i < shapes->size(); ++i)
        if ((*shapes)[i].is_object() && (*shapes)[i].contains("interior_medium"))
            return "/shapes/" + std::to_string(i) + "/interior_medium";
    return "";
}

// Reads the camera, media, materials, shapes and lights into `builder`.
void readSceneObjects(ObjectReader& root, const RenderSettings& render, const AssetResolver& assets,
                      SceneBuilder& builder) {
    ObjectReader cj(root.raw("camera"), root.pointerTo("camera"));
    const CameraReading view = readCamera(cj);
    builder.setCamera(view.camera, render.width, render.height);
    builder.setRenderOrigin(view.origin);

    if (const Json* m = root.rawOptional("medium")) {
        ObjectReader mj(*m, root.pointerTo("medium"));
        builder.setSceneMedium(builder.addMedium(makeMedium(mj)));
    }

    MaterialCatalog materials(root.rawOptional("materials"), root.pointerTo("materials"), builder,
                              assets);

    const Json& shapes = root.raw("shapes");
    if (!shapes.is_array()) root.fail("shapes", "expected an array of shapes");
    for (size_t i = 0; i < shapes.size(); ++i) {
        ObjectReader sj(shapes[i], root.pointerTo("shapes") + "/" + std::to_string(i));
        readShape(sj, materials, builder, assets, view);
    }

    if (const Json* lights = root.rawOptional("lights")) {
        if (!lights->is_array()) root.fail("lights", "expected an array of lights");
        for (size_t i = 0; i < lights->size(); ++i) {
            ObjectReader lj((*lights)[i], root.pointerTo("lights") + "/" + std::to_string(i));
            builder.addLight(makeLight(lj, assets, view.worldToRender));
        }
    }
}

// The top-level keys readSceneObjects reads (camera and shapes required).
constexpr const char* kSceneObjectKeys[] = {"camera", "medium", "materials", "shapes", "lights"};

// Marks the scene objects read without building them (the scene came from a cache).
void skipSceneObjects(ObjectReader& root) {
    for (const char* key : kSceneObjectKeys)
        root.rawOptional(key);
}

// Everything the built scene depends on: the scene objects, the render settings the builder
// takes (resolution, light selection) and the asset search path. Seeds, sample counts, path
// lengths, samplers and integrators are not in it: they never reach the scene.
std::string sceneCacheKey(const Json& document, const RenderSettings& render,
                          const AssetResolver& assets) {
    Json key = {{"resolution", {render.width, render.height}},
                {"light_selection", int(render.lightSelection)},
                {"search_path", Json::array()}};
    for (const std::filesystem::path& dir : assets.searchPath())
        key["search_path"].push_back(dir.string());
    for (const char* name : kSceneObjectKeys)
        if (const auto it = document.find(name); it != document.end()) key[name] = *it;
    return key.dump();
}

}  // namespace

ReconstructionFilter LoadedScene::filmFilter() const {
    return integrator->formsOwnImage() ? ReconstructionFilter()
                                       : ReconstructionFilter(render.filter);
}

ScheduleInputs LoadedScene::scheduleInputs(uint32_t spp, double timeLimit) const {
    return ScheduleInputs{*scene,    render.width, render.height, spp,
                          timeLimit, render.seed,  render.filter};
}

LoadedScene loadScene(const Json& document, const AssetResolver& assets, SceneCache* cache) {
    ObjectReader root(document, "", sceneRootKeys());
    if (root.has("description")) root.string("description");

    PathSettings path;
    RenderSettings render;
    {
        static const Json empty = Json::object();
        const Json* r = root.rawOptional("render");
        ObjectReader rj(r ? *r : empty, root.pointerTo("render"));
        render = readRenderSettings(rj, &path);
    }

    const std::string cacheKey = cache ? sceneCacheKey(document, render, assets) : std::string();
    std::shared_ptr<const Scene> scene = cache ? cache->find(cacheKey, assets) : nullptr;
    std::optional<SceneBuilder> builder;
    std::vector<AssetStamp> files;  // the files a newly built scene is made from
    if (scene) {
        skipSceneObjects(root);
    } else {
        builder.emplace();
        readSceneObjects(root, render, cache ? assets.recordingInto(&files) : assets, *builder);
    }

    BuiltIntegrator built;
    {
        static const Json defaultIntegrator = {{"type", "path_mis"}};
        const Json* ij = root.rawOptional("integrator");
        ObjectReader reader(ij ? *ij : defaultIntegrator, root.pointerTo("integrator"));
        built = techniqueRegistry().makeIntegrator(reader, path);
    }
    const Integrator& integrator = *built.integrator;
    checkStructuredSampleCount(render, integrator, root.pointerTo("render") + "/spp");
    const std::string mediumPointer = firstMediumPointer(document);
    if (!mediumPointer.empty() && !techniqueRegistry().rendersMedia(integrator.name()))
        throw ConfigError(mediumPointer, "the " + integrator.name() +
                                             " integrator does not render participating media; "
                                             "use one that does: " +
                                             quotedNames(techniqueRegistry().mediaIntegrators()));
    root.finish();

    if (!scene) {
        scene = builder->build(render.lightSelection);
        if (scene->lights().empty())
            throw ConfigError("", "the scene has no light: add an emitter shape or a light");
        if (cache) cache->insert(cacheKey, scene, std::move(files));
    }
    LoadedScene loaded;
    loaded.scene = std::move(scene);
    const auto start = std::chrono::steady_clock::now();
    built.integrator->prepare(*loaded.scene);
    loaded.prepareSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    loaded.integrator = std::move(built.integrator);
    loaded.schedule = std::move(built.schedule);
    loaded.render = render;
    return loaded;
}

}  // namespace rr
