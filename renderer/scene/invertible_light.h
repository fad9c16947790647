// A light capability: the inverse of its sampling, for estimators whose importance maps live on
// a light's sample coordinates u and must find the map's density at a point that another
// strategy (BSDF sampling) hit (TAIS's point-on-light map, Cline et al. 2008). A light that can
// invert its sampling also implements InvertibleLight (area lights on shapes with an inverse,
// environments); an estimator finds it once per light (invertibleLight) and leaves the other
// lights' coordinates as they are.
#pragma once

#include "scene/light.h"

namespace rr {

class InvertibleLight {
  public:
    virtual ~InvertibleLight() = default;
    // The u for which sample(reference, u, …) yields the point `point` on this light, seen in
    // unit direction `direction` from `reference` (infinite lights: the direction alone, `point`
    // is ignored). False when no u yields the point (the light's density is zero there). Where
    // sample() is not injective (a pole of a sphere, the seam of a lat-long map) one of the
    // preimages.
    virtual bool invertSample(const LightReference& reference, const Vec3& direction,
                              const Vec3& point, Vec2* u) const = 0;
    // Whether invertSample() is implemented for this light after all: false for an area light
    // whose shape has no inverse or moves (Shape::invertSampleDirection).
    virtual bool invertsSamples() const { return true; }
};

// `light`'s inverse, or nullptr when it cannot invert its sampling.
inline const InvertibleLight* invertibleLight(const Light& light) {
    const auto* inverse = dynamic_cast<const InvertibleLight*>(&light);
    return inverse && inverse->invertsSamples() ? inverse : nullptr;
}

}  // namespace rr
