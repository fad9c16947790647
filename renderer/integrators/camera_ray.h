// The camera ray of a pixel sample. Its coordinates are drawn first (position in the pixel, and
// the lens point and shutter time only when the camera uses them), so a technique can warp the
// lens and time coordinates (TAIS's maps) before the ray is formed.
#pragma once

#include "sampling/sampler.h"
#include "scene/camera.h"

namespace rr {

struct CameraSample {
    Vec2 film;                 // position in the pixel, [0, 1)²
    Vec2 lens = {0.5f, 0.5f};  // point on the aperture (the centre for a pinhole)
    float time = 0;            // shutter coordinate
};

CameraSample drawCameraSample(const Camera& camera, const PixelSample& sample);

// The sample's position in its pixel, [0, 1)²: the FilmPosition decision, or the centre for a
// camera that traces pixel centres. A splatting film (render/film.h) places the sample's value
// by it, so no technique may warp this decision.
Vec2 filmOffset(const Camera& camera, const PixelSample& sample);

// The ray through pixel (x, y) for the coordinates `c`.
inline Ray cameraRay(const Camera& camera, int x, int y, const CameraSample& c) {
    return camera.generateRay(
        Vec2(static_cast<float>(x) + c.film.x, static_cast<float>(y) + c.film.y), c.lens, c.time);
}

inline Ray generateCameraRay(const Camera& camera, int x, int y, const PixelSample& sample) {
    return cameraRay(camera, x, y, drawCameraSample(camera, sample));
}

}  // namespace rr
