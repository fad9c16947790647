// Phase function interface: the angular distribution of light scattered in a medium.
// Directions follow the BSDF convention: `wo` and `wi` are unit world-space vectors pointing
// away from the scattering point, wo back along the arriving path (towards the camera) and
// wi towards where light comes from. The scattering angle θ is between the propagation
// directions before and after scattering, −wi and wo, or equally between −wo and wi:
// cos θ = −dot(wo, wi); cos θ = 1 is forward scattering (the path goes straight on).
// p integrates to 1 over wi; the functions here are sampled exactly (pdf = p), so a phase
// sample's weight p/pdf is 1.
#pragma once

#include "math/vector.h"

namespace rr {

class PhaseFunction {
  public:
    virtual ~PhaseFunction() = default;

    // p(wo, wi) per steradian.
    virtual float eval(const Vec3& wo, const Vec3& wi) const = 0;
    // Solid-angle density with which sample() yields wi.
    virtual float pdf(const Vec3& wo, const Vec3& wi) const = 0;
    // Draws wi from `u` (the BsdfDirection decision at the medium vertex: TAIS's scatter-
    // direction map can warp it); returns its pdf (0: no sample).
    virtual float sample(const Vec3& wo, Vec2 u, Vec3* wi) const = 0;
};

}  // namespace rr
