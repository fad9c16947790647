#include "support/scene_testing.h"

#include <cmath>

#include "config/config_error.h"
#include "loader/factories.h"

namespace rr::test {

LoadedScene loadSceneText(const std::string& json) {
    return loadSceneJson(parseSceneText(json, "test scene"));
}

LoadedScene loadSceneJson(const Json& document) {
    return loadScene(document, AssetResolver::standard(TEST_SCENES_DIR));
}

LoadedScene loadSceneFile(const std::string& name, const std::vector<std::string>& overrides) {
    Json doc = readSceneFile(std::string(TEST_SCENES_DIR) + "/" + name);
    for (const std::string& o : overrides)
        applyOverride(doc, o);
    return loadScene(doc, AssetResolver::standard(TEST_SCENES_DIR));
}

std::unique_ptr<Material> materialFromJson(const std::string& json) {
    const Json j = Json::parse(json);
    ObjectReader reader(j, "/materials/m");
    const MaterialReferences none = [](const Json&, const std::string& pointer) -> const Material* {
        throw ConfigError(pointer, "no material references in this test");
    };
    return makeMaterial(reader, AssetResolver({}), none);
}

Ray inFileSpace(const Scene& scene, Ray ray) {
    const Vec3d o = scene.renderOrigin();
    ray.origin = toFloat({ray.origin.x + o.x, ray.origin.y + o.y, ray.origin.z + o.z});
    return ray;
}

TestRender renderScene(const LoadedScene& scene, uint32_t spp, uint32_t seed, int threads) {
    TestRender r{Film(scene.render.width, scene.render.height, scene.filmFilter()), {}};
    RenderOptions options;
    options.seed = seed;
    options.threads = threads;
    options.sampler = scene.render.sampler;
    options.samplerSetSize = spp;
    const std::unique_ptr<RenderSchedule> schedule = scene.schedule(
        ScheduleInputs{*scene.scene, scene.render.width, scene.render.height, spp, 0, seed,
                       scene.render.filter});
    r.stats = render(*schedule, options, r.film);
    return r;
}

Estimate regionMean(const Film& film, int c, int x0, int y0, int x1, int y1) {
    double sum = 0, variance = 0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            sum += film.mean(x, y)[c];
            variance += film.varianceOfMean(x, y)[c];
        }
    const double n = double(x1 - x0) * (y1 - y0);
    return {sum / n, std::sqrt(variance) / n};
}

}  // namespace rr::test
