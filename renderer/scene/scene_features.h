// What a scene uses, found from its public queries: recorded in the output (renderer.features),
// and read by techniques that steer only what the scene has (TAIS chooses its maps by it).
// Paths skip what a scene does not use at no cost.
#pragma once

#include "scene/scene.h"

namespace rr {

struct SceneFeatures {
    bool motionBlur = false;  // some shape moves and the shutter is open for a while
    bool thinLens = false;    // the camera has an aperture
    bool media = false;       // participating media: a scene medium or a shape's interior
    // Some surface both reflects and transmits (glass): its paths bifurcate.
    bool bifurcation = false;
};

SceneFeatures sceneFeatures(const Scene& scene);

}  // namespace rr
