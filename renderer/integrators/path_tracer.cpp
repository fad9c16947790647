#include "integrators/path_tracer.h"

#include "integrators/path_walk.h"

namespace rr {

nlohmann::json PathTracer::parameters() const {
    return {{"type", name()}, {"max_depth", settings_.maxDepth}, {"rr_depth", settings_.rrDepth}};
}

Rgb PathTracer::estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const {
    const Ray cameraRay = generateCameraRay(scene.camera(), x, y, sample);
    ++rays.camera;
    StandardSampling standard(scene, sample);
    if (scene.features().media)
        return PathWalk<true, StandardSampling>(scene, standard, rays, settings_, nee_, cameraRay)
            .run();
    return PathWalk<false, StandardSampling>(scene, standard, rays, settings_, nee_, cameraRay)
        .run();
}

}  // namespace rr
