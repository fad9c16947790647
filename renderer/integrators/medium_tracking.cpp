#include "integrators/medium_tracking.h"

#include <algorithm>
#include <limits>

namespace rr {

namespace {

// Attenuates by `medium` (if any) over `distance`.
void attenuate(const Medium* medium, float distance, Rgb* transmittance, float* survival) {
    if (!medium) return;
    *transmittance *= medium->transmittance(distance);
    *survival *= medium->survival(distance);
}

}  // namespace

Rgb shadowTransmittance(const Scene& scene, const Ray& ray, const Medium* medium, bool toInfinity,
                        float* survival, RayCounters& rays) {
    const Vec3 target = ray.origin + ray.direction * ray.tMax;
    Rgb transmittance(1.0f);
    *survival = 1;
    Ray segment = ray;
    for (int crossing = 0;; ++crossing) {
        ++rays.shadow;
        SurfaceHit hit;
        if (!scene.intersect(segment, &hit)) break;
        if (!hit.shape->isMediumBoundary() || crossing == kMaxBoundaryCrossings) return Rgb(0.0f);
        attenuate(medium, hit.distance, &transmittance, survival);
        medium = mediumOnSide(scene, hit, segment.direction, medium);
        segment.origin =
            offsetRayOrigin(hit.position, hit.geometricNormal, segment.direction, hit.errorScale);
        segment.tMax = std::max(0.0f, dot(target - segment.origin, segment.direction));
        if (segment.tMax == 0) break;  // the boundary lies at the target
    }
    attenuate(medium, toInfinity ? std::numeric_limits<float>::infinity() : segment.tMax,
              &transmittance, survival);
    return transmittance;
}

}  // namespace rr
