// The scene's "camera" object: pinhole or thin lens, field of view, shutter interval.
//
// It also fixes the rendering space: the renderer works in the scene file's coordinates
// translated so that the camera sits at the origin (as pbrt-v4's default rendering space,
// "camera-world"). Float spacing is then finest near the camera, where the image resolves the
// scene, and a scene placed 10^6 units from the file's origin renders as it does at the origin
// (configs/stress/offset_1e6.json): the loader moves every position into rendering space in
// double, before rounding to float.
#pragma once

#include "config/json_reader.h"
#include "math/transform.h"
#include "scene/camera.h"

namespace rr {

struct CameraReading {
    CameraSettings camera;    // in rendering space: at the origin
    Vec3d origin;             // the camera's position in the file's coordinates
    Transform worldToRender;  // the translation by -origin
};

CameraReading readCamera(ObjectReader& json);

// The keys of the "camera" object.
const KeyTable& cameraKeys();

}  // namespace rr
