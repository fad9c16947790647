#include "integrators/camera_ray.h"

namespace rr {

CameraSample drawCameraSample(const Camera& camera, const PixelSample& sample) {
    CameraSample c;
    c.film = camera.samplesPixelArea() ? sample.get2D(Decision::FilmPosition) : Vec2(0.5f, 0.5f);
    if (camera.isThinLens()) c.lens = sample.get2D(Decision::Lens);
    if (camera.hasShutterInterval()) c.time = sample.get1D(Decision::Time);
    return c;
}

}  // namespace rr
