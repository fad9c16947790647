// Participating medium interface. A path that travels through a medium either collides (and
// scatters, weighted by the single-scattering albedo) or passes the whole segment; that choice
// and the collision distance are one named decision, MediumDistance (TAIS §3.2's "scatter
// distance" map warps it).
//
// Free-flight sampling by inversion of the survival function S(t) = P(no collision before t):
// the decision's u gives the flight's survival budget v = 1 − u ∈ (0, 1], and the flight
// collides at the t where S(t) = v. On a segment of length tMax it collides iff v > S(tMax);
// otherwise it passes with the budget v / S(tMax) left for the medium beyond the next
// boundary, which is the inversion of the survival function of the whole ray, segment by
// segment (no second decision is needed when a ray crosses index-matched boundaries, and the
// map from u to the distance along the ray stays monotone, as a preimage-space map wants).
// Only homogeneous media exist so far: the interface takes distances along a segment; a
// heterogeneous medium would also take the ray.
#pragma once

#include "math/rgb.h"
#include "scene/phase_function.h"

namespace rr {

struct FreeFlight {
    bool collided = false;
    float distance = 0;  // the collision's distance (< tMax); unset when the flight passed
    // Throughput factor: at a collision Tr(t)·σs / pdf(t) (the estimator continues with the
    // phase function, the albedo in the weight); when the flight passes,
    // Tr(tMax) / S(tMax).
    Rgb weight;
    float survival = 1;    // S(tMax) when the flight passed (a probability, for MIS)
    float budgetLeft = 1;  // v / S(tMax) when the flight passed, for the next medium
};

class Medium {
  public:
    virtual ~Medium() = default;

    // Transmittance e^{−∫σt} over a segment of length `distance` (may be infinite).
    virtual Rgb transmittance(float distance) const = 0;
    // S(distance): the probability that free-flight sampling passes a segment of that length.
    virtual float survival(float distance) const = 0;
    // The free-flight decision on a segment of length tMax (infinite for a ray that leaves the
    // scene) with survival budget `budget` ∈ (0, 1].
    virtual FreeFlight sampleFreeFlight(float budget, float tMax) const = 0;
    virtual const PhaseFunction& phase() const = 0;
};

}  // namespace rr
