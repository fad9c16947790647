#include "scene/scene_features.h"

namespace rr {

SceneFeatures sceneFeatures(const Scene& scene) {
    SceneFeatures f;
    bool anyMotion = false;
    for (const std::unique_ptr<Shape>& shape : scene.shapes()) {
        anyMotion = anyMotion || shape->hasMotion();
        const Material* m = shape->material();
        f.bifurcation =
            f.bifurcation || (m && (m->lobes() & kReflection) && (m->lobes() & kTransmission));
    }
    f.motionBlur = anyMotion && scene.camera().hasShutterInterval();
    f.thinLens = scene.camera().isThinLens();
    f.media = scene.hasMedia();
    return f;
}

}  // namespace rr
