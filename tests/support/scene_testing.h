// In-process rendering of scene documents for tests, and the statistics to judge the result:
// means over pixel regions with their standard errors taken from the per-pixel variance.
#pragma once

#include <memory>
#include <string>

#include "loader/scene_loader.h"
#include "render/film.h"
#include "render/renderer.h"

namespace rr::test {

LoadedScene loadSceneText(const std::string& json);
LoadedScene loadSceneJson(const Json& document);
// A scene from configs/scenes by file name, with `--set`-style overrides applied.
LoadedScene loadSceneFile(const std::string& name, const std::vector<std::string>& overrides = {});
// A material from its JSON object (one that refers to no other material), read as if at
// /materials/m.
std::unique_ptr<Material> materialFromJson(const std::string& json);

// A ray of the scene (a camera ray, say) in the scene file's coordinates, which the tests' own
// geometry uses: rendering space is translated so that the camera is at its origin.
Ray inFileSpace(const Scene& scene, Ray ray);

struct TestRender {
    Film film;
    RenderStats stats;
};
TestRender renderScene(const LoadedScene& scene, uint32_t spp, uint32_t seed = 1, int threads = 0);

struct Estimate {
    double mean = 0;
    double standardError = 0;
};
// Mean of channel c (0..2) over pixels [x0, x1) × [y0, y1); the standard error combines the
// pixels' variances of the mean (pixels are independent).
Estimate regionMean(const Film& film, int c, int x0, int y0, int x1, int y1);
inline Estimate imageMean(const Film& film, int c) {
    return regionMean(film, c, 0, 0, film.width(), film.height());
}

}  // namespace rr::test
