// How an environment light draws the directions of its light samples (`sampling` in a scene's
// environment light). `luminance` follows the map (∝ luminance × solid angle: pbrt-v1's
// `infinitesample` plugin, and our default); the other two ignore the map, as pbrt-v1's plain
// `infinite` light does, for comparisons configured like the papers' renderers:
//  - `cosine`: cosine-weighted about the receiver's shading normal over *both* hemispheres,
//    each with probability ½, so the density is |cos θ|/2π (pbrt-v1 lights/infinite.cpp,
//    Sample_L with a normal); where the receiver has no normal (a medium), uniform over the
//    sphere, as pbrt-v1's overload without a normal;
//  - `uniform`: uniform over the sphere, 1/4π.
#pragma once

#include <cstdint>

#include "math/vector.h"
#include "scene/light.h"

namespace rr {

enum class EnvSampling : uint8_t { Luminance, Cosine, Uniform };

// The direction-only samplers (`cosine`, `uniform`), in world space; `luminance` is the map's
// own and not handled here. sampleEnvDirection returns false when the density is zero (never
// for these two, save a degenerate u).
bool sampleEnvDirection(EnvSampling how, const LightReference& reference, Vec2 u, Vec3* w,
                        float* pdf);
float envDirectionPdf(EnvSampling how, const LightReference& reference, const Vec3& w);
// The inverse: the u for which sampleEnvDirection yields `w` (one of them where the map is
// not injective); false where the density of `w` is zero (a cosine-sampled direction in the
// receiver's tangent plane).
bool invertEnvDirection(EnvSampling how, const LightReference& reference, const Vec3& w, Vec2* u);

}  // namespace rr
