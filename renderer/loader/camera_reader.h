// The scene's "camera" object: pinhole or thin lens, field of view, shutter interval.
#pragma once

#include "config/json_reader.h"
#include "scene/camera.h"

namespace rr {

CameraSettings readCamera(ObjectReader& json);

}  // namespace rr
