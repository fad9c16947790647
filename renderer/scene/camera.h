// Pinhole and thin-lens perspective cameras with a look-at placement and a shutter interval.
// Scene time runs over [0, 1]; the shutter selects [open, close] within it. The camera's
// importance is constant per pixel, so an estimate is the radiance carried by the ray.
#pragma once

#include "math/vector.h"
#include "scene/ray.h"

namespace rr {

struct CameraSettings {
    Vec3 position{0, 0, 0};
    Vec3 lookAt{0, 0, -1};
    Vec3 up{0, 1, 0};
    float verticalFovDegrees = 40;
    float apertureRadius = 0;  // 0: pinhole
    float focusDistance = 1;
    float shutterOpen = 0, shutterClose = 0;
    // False: every camera ray passes through its pixel's centre (no film-position decision), so
    // that an image measures a pixel estimator's error alone, without the pixel's footprint
    // (two-stage fig. 8's convergence per sample count).
    bool samplePixelArea = true;
};

class Camera {
  public:
    Camera(const CameraSettings& settings, int width, int height);

    // Ray through film position (x, y) in pixels (y down), lens sample on [0,1)², shutter
    // sample on [0,1). Lens and time samples are ignored when the camera has no aperture or
    // no shutter interval.
    Ray generateRay(Vec2 film, Vec2 lens, float shutter) const;

    bool isThinLens() const { return settings_.apertureRadius > 0; }
    bool hasShutterInterval() const { return settings_.shutterClose > settings_.shutterOpen; }
    bool samplesPixelArea() const { return settings_.samplePixelArea; }
    const CameraSettings& settings() const { return settings_; }
    int width() const { return width_; }
    int height() const { return height_; }

  private:
    CameraSettings settings_;
    int width_, height_;
    Vec3 forward_, right_, up_;
    float tanHalfFov_, aspect_;
};

}  // namespace rr
