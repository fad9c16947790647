#include "scene/camera.h"

#include <cmath>

#include "sampling/warps.h"

namespace rr {

Camera::Camera(const CameraSettings& settings, int width, int height)
    : settings_(settings), width_(width), height_(height) {
    forward_ = normalize(settings.lookAt - settings.position);
    right_ = normalize(cross(forward_, settings.up));
    up_ = cross(right_, forward_);
    tanHalfFov_ = std::tan(0.5f * settings.verticalFovDegrees * kPi / 180.0f);
    aspect_ = static_cast<float>(width) / static_cast<float>(height);
}

Ray Camera::generateRay(Vec2 film, Vec2 lens, float shutter) const {
    const float sx = (2.0f * film.x / width_ - 1.0f) * aspect_ * tanHalfFov_;
    const float sy = (1.0f - 2.0f * film.y / height_) * tanHalfFov_;
    const Vec3 pinholeDir = forward_ + right_ * sx + up_ * sy;  // forward component is 1

    Ray ray;
    // Without a shutter interval the loader bakes moving shapes at the shutter instant, so
    // rays carry time 0 and the scene has no motion at all.
    ray.time = hasShutterInterval() ? settings_.shutterOpen +
                                          shutter * (settings_.shutterClose - settings_.shutterOpen)
                                    : 0.0f;
    if (!isThinLens()) {
        ray.origin = settings_.position;
        ray.direction = normalize(pinholeDir);
        return ray;
    }
    // Thin lens: all rays through the same film point meet on the plane of focus.
    const Vec3 focusPoint = settings_.position + pinholeDir * settings_.focusDistance;
    const Vec2 d = squareToUniformDisk(lens);
    ray.origin = settings_.position + (right_ * d.x + up_ * d.y) * settings_.apertureRadius;
    ray.direction = normalize(focusPoint - ray.origin);
    return ray;
}

}  // namespace rr
