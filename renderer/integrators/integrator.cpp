#include "integrators/integrator.h"

namespace rr {

Ray generateCameraRay(const Camera& camera, int x, int y, const PixelSample& sample) {
    const Vec2 f = sample.get2D(Decision::FilmPosition);
    const Vec2 lens = camera.isThinLens() ? sample.get2D(Decision::Lens) : Vec2(0.5f, 0.5f);
    const float time = camera.hasShutterInterval() ? sample.get1D(Decision::Time) : 0.0f;
    return camera.generateRay(Vec2(static_cast<float>(x) + f.x, static_cast<float>(y) + f.y), lens,
                              time);
}

float emissionMisWeight(bool countInFull, float bsdfPdf, float lightPdf) {
    return countInFull ? 1.0f : powerHeuristic(1, bsdfPdf, 1, lightPdf);
}

}  // namespace rr
