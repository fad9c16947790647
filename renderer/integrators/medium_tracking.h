// Which medium a ray travels through, and the transmittance of shadow rays across media.
// A ray starts in the scene's medium (the camera must be outside every shape with an interior
// medium); crossing the surface of a shape that has an interior medium switches to it when
// the ray goes inwards (against the geometric normal) and back to the scene's medium when it
// goes outwards. Nested media are not supported: leaving a shape always returns to the scene's
// medium, so shapes with interior media must not overlap or contain one another. Crossing a
// shape without an interior medium keeps the current medium (a glass sphere in fog is foggy
// inside unless it has an interior medium of its own, which may be {σa = σs = 0}).
#pragma once

#include "integrators/integrator.h"

namespace rr {

// A safety cap on the boundaries one ray may pass through (degenerate geometry could
// otherwise trap a ray between two coincident boundaries).
inline constexpr int kMaxBoundaryCrossings = 1000;

// The medium on the side of `hit` that the unit direction `w` points to, for a ray that
// reached the surface travelling in `current`.
inline const Medium* mediumOnSide(const Scene& scene, const SurfaceHit& hit, const Vec3& w,
                                  const Medium* current) {
    const Medium* interior = hit.shape->interiorMedium();
    if (!interior) return current;
    return dot(w, hit.geometricNormal) < 0 ? interior : scene.medium();
}

// Transmittance along a shadow ray that starts in `medium`: the product of the media's
// transmittances over the segments between the index-matched boundaries it passes, black when
// any other surface is in the way. With `toInfinity` (infinite lights, whose shadow-ray target
// is only a stand-in beyond the scene) the last segment extends to infinity, as the escaping
// paths that reach such lights do. `survival` receives the probability that free-flight
// sampling passes the same segments (the density factor a scattered path pays to reach the
// light, for MIS). Each ray traced counts as a shadow ray.
Rgb shadowTransmittance(const Scene& scene, const Ray& ray, const Medium* medium, bool toInfinity,
                        float* survival, RayCounters& rays);

}  // namespace rr
