// A light capability: a cheaper stand-in for its own sampler (Light::sample), for estimators
// that draw many candidates and finish few (resampled importance sampling's ĝ needs only an
// approximation of the integrand, Talbot et al. 2005). A stand-in draws from a density that may
// differ from sample()'s (the sample's `pdf` is the stand-in's own, exact) and may give an
// approximate `radiance`; exactRadiance() gives the light's true radiance along the sample. A
// light that has one also implements LightStandIn (an environment map draws from blocks of
// texels: EnvironmentMap); lights without one are drawn by their own sampler in its place.
#pragma once

#include <span>
#include <vector>

#include "scene/light.h"

namespace rr {

class LightStandIn {
  public:
    virtual ~LightStandIn() = default;
    virtual bool sampleStandIn(const LightReference& reference, Vec2 u, float time,
                               LightSample* out) const = 0;
    // The radiance that arrives along a sample of sampleStandIn().
    virtual Rgb exactRadiance(const LightSample& s) const = 0;
};

// The stand-ins of a scene's lights, found once (when an estimator is prepared), by light index.
class LightStandIns {
  public:
    explicit LightStandIns(std::span<const Light* const> lights) {
        for (const Light* light : lights)
            byIndex_.push_back(dynamic_cast<const LightStandIn*>(light));
    }
    LightStandIns() = default;

    // `light`'s stand-in, or nullptr when it has none.
    const LightStandIn* of(const Light& light) const {
        return byIndex_[static_cast<size_t>(light.index())];
    }

  private:
    std::vector<const LightStandIn*> byIndex_;
};

// A point on `light` from its stand-in in `standIns`, or from its own sampler when it has none
// there or `standIns` is nullptr.
inline bool sampleLightOrStandIn(const Light& light, const LightStandIns* standIns,
                                 const LightReference& reference, Vec2 u, float time,
                                 LightSample* out) {
    const LightStandIn* standIn = standIns ? standIns->of(light) : nullptr;
    return standIn ? standIn->sampleStandIn(reference, u, time, out)
                   : light.sample(reference, u, time, out);
}

}  // namespace rr
