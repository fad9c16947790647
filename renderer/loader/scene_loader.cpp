#include "loader/scene_loader.h"

#include <chrono>
#include <string>

#include "config/type_table.h"
#include "loader/camera_reader.h"
#include "loader/factories.h"
#include "loader/material_catalog.h"
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

}  // namespace

LoadedScene loadScene(const Json& document, const AssetResolver& assets) {
    ObjectReader root(document, "");
    root.getString("description", "");

    PathSettings path;
    RenderSettings render;
    {
        static const Json empty = Json::object();
        const Json* r = root.rawOptional("render");
        ObjectReader rj(r ? *r : empty, root.pointerTo("render"));
        render = readRenderSettings(rj, &path);
    }

    SceneBuilder builder;
    CameraSettings camera;
    {
        ObjectReader cj(root.raw("camera"), root.pointerTo("camera"));
        camera = readCamera(cj);
    }
    builder.setCamera(camera, render.width, render.height);

    // Where the first medium is declared, for the error if the integrator cannot render it.
    std::string mediumPointer;
    if (const Json* m = root.rawOptional("medium")) {
        ObjectReader mj(*m, root.pointerTo("medium"));
        builder.setSceneMedium(builder.addMedium(makeMedium(mj)));
        mediumPointer = mj.pointer();
    }

    MaterialCatalog materials(root.rawOptional("materials"), root.pointerTo("materials"), builder,
                              assets);

    const Json& shapes = root.raw("shapes");
    if (!shapes.is_array()) root.fail("shapes", "expected an array of shapes");
    for (size_t i = 0; i < shapes.size(); ++i) {
        ObjectReader sj(shapes[i], root.pointerTo("shapes") + "/" + std::to_string(i));
        readShape(sj, materials, builder, assets, camera);
        if (mediumPointer.empty() && shapes[i].contains("interior_medium"))
            mediumPointer = sj.pointerTo("interior_medium");
    }

    if (const Json* lights = root.rawOptional("lights")) {
        if (!lights->is_array()) root.fail("lights", "expected an array of lights");
        for (size_t i = 0; i < lights->size(); ++i) {
            ObjectReader lj((*lights)[i], root.pointerTo("lights") + "/" + std::to_string(i));
            builder.addLight(makeLight(lj, assets));
        }
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
    if (!mediumPointer.empty() && !techniqueRegistry().rendersMedia(integrator.name()))
        throw ConfigError(mediumPointer, "the " + integrator.name() +
                                             " integrator does not render participating media; "
                                             "use one that does: " +
                                             quotedNames(techniqueRegistry().mediaIntegrators()));
    root.finish();

    LoadedScene loaded;
    loaded.scene = builder.build(render.lightSelection);
    if (loaded.scene->lights().empty())
        throw ConfigError("", "the scene has no light: add an emitter shape or a light");
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
