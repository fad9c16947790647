#include "integrators/camera_ray.h"

namespace rr {

Vec2 filmOffset(const Camera& camera, const PixelSample& sample) {
    return camera.samplesPixelArea() ? sample.get2D(Decision::FilmPosition) : Vec2(0.5f, 0.5f);
}

CameraSample drawCameraSample(const Camera& camera, const PixelSample& sample) {
    CameraSample c;
    c.film = filmOffset(camera, sample);
    if (camera.isThinLens()) c.lens = sample.get2D(Decision::Lens);
    if (camera.hasShutterInterval()) c.time = sample.get1D(Decision::Time);
    return c;
}

}  // namespace rr
