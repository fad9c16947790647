// Light interface. Next-event estimation asks a light for a direction towards it with a
// solid-angle density; MIS asks for the density of a direction found by BSDF sampling.
// How the papers' other lights fit:
//  - spot: a delta light like PointLight, its intensity shaped by the cone and falloff;
//  - convex polygon: an AreaLight on a polygon Shape (a triangle fan sampled by solid
//    angle), no change here;
//  - environment map: an infinite light (isInfinite()). sample() returns a direction with the
//    map's solid-angle pdf and `position` outside the scene's bounding sphere (the shadow ray
//    runs past every surface); rays that escape the scene see escapedRadiance(), and MIS
//    weighs them with directionPdf().
#pragma once

#include <cstdint>

#include "math/rgb.h"
#include "math/vector.h"
#include "scene/surface_hit.h"

namespace rr {

// Which of a light's samplers to draw from: its own (sample()), or the cheaper stand-in that
// estimators drawing many candidates and finishing few use (sampleProxy(), RIS).
enum class LightDraw : uint8_t { Exact, Proxy };

// Where light is gathered: the point, and at a surface its shading normal (unit; zero in a
// medium or where there is none). Only lights whose sampling follows the receiver's
// orientation read the normal (an environment sampled cosine-weighted: env_sampling.h), so a
// point converts to a reference without one.
struct LightReference {
    LightReference(const Vec3& point_, const Vec3& normal_ = Vec3(0.0f))  // NOLINT: implicit
        : point(point_), normal(normal_) {}
    Vec3 point;
    Vec3 normal;
};

struct LightSample {
    Vec3 direction;        // unit, from the reference point towards the light
    Vec3 position;         // sampled point on the light (shadow-ray target)
    Vec3 normal;           // light surface normal there (zero for point lights)
    float errorScale = 0;  // of `position`, for lifting the shadow ray's end off the light
    Rgb radiance;          // arriving radiance (for delta lights: intensity / distance²)
    float pdf = 0;         // solid angle; 1 for delta lights
    bool isDelta = false;
};

class Light {
  public:
    virtual ~Light() = default;

    virtual bool sample(const LightReference& reference, Vec2 u, float time,
                        LightSample* out) const = 0;
    // A cheaper stand-in for sample(), for estimators that draw many candidates and finish
    // few (RIS's ĝ needs only an approximation of the integrand): a sample from a density that
    // may differ from sample()'s (`pdf` is the stand-in's own, exact) whose `radiance` may be
    // approximate; exactRadiance() gives the light's true radiance for it. By default sample()
    // itself; an environment map draws from blocks of texels (EnvironmentMap).
    virtual bool sampleProxy(const LightReference& reference, Vec2 u, float time,
                             LightSample* out) const {
        return sample(reference, u, time, out);
    }
    // The radiance that arrives along a sample of sampleProxy() (or of sample(): its own).
    virtual Rgb exactRadiance(const LightSample& s) const { return s.radiance; }
    // sample() or sampleProxy(), as `how` says.
    bool draw(LightDraw how, const LightReference& reference, Vec2 u, float time,
              LightSample* out) const {
        return how == LightDraw::Proxy ? sampleProxy(reference, u, time, out)
                                       : sample(reference, u, time, out);
    }
    // Solid-angle density with which sample() from `reference` yields the point `hit` on this
    // light; zero for delta lights.
    virtual float pdf(const Vec3& reference, const SurfaceHit& hit) const = 0;
    // Total emitted power (flux), used for light selection by power.
    virtual Rgb power() const = 0;
    virtual bool isDelta() const = 0;

    // Infinite lights surround the scene: they are seen by rays that hit nothing.
    virtual bool isInfinite() const { return false; }
    // Radiance arriving along a ray that leaves the scene in direction `w` (unit, world).
    virtual Rgb escapedRadiance(const Vec3& /*w*/) const { return Rgb(0.0f); }
    // Solid-angle density with which sample() from `reference` yields direction `w` (infinite
    // lights).
    virtual float directionPdf(const LightReference& /*reference*/, const Vec3& /*w*/) const {
        return 0;
    }
    // The inverse of sample(), for TAIS's point-on-light importance map, which lives on the
    // coordinates u: the u for which sample(reference, u, …) yields the point `point` on this
    // light, seen in unit direction `direction` from `reference` (infinite lights: the
    // direction alone, `point` is ignored). False when the light cannot invert its sampling
    // (delta lights, shapes whose sampling has no implemented inverse, moving shapes: see
    // Shape::invertSampleDirection) or when no u yields the point (the light's density is zero
    // there); TAIS then leaves that light's coordinates unwarped. Where sample() is not
    // injective (a pole of a sphere, the seam of a lat-long map) one of the preimages.
    virtual bool invertSample(const LightReference& /*reference*/, const Vec3& /*direction*/,
                              const Vec3& /*point*/, Vec2* /*u*/) const {
        return false;
    }
    // Called once the scene is built, before power() is used: infinite lights need the
    // bounding sphere of the scene for their shadow-ray targets and their power.
    virtual void preprocess(const Vec3& /*sceneCenter*/, float /*sceneRadius*/) {}

    // Whether invertSample() can map this light's samples back to their coordinates (true
    // for the lights that implement it; it may still refuse points of zero density).
    virtual bool canInvertSample() const { return false; }

    // Index in the scene's light list; set by the scene.
    int index() const { return index_; }
    void setIndex(int i) { index_ = i; }

  private:
    int index_ = -1;
};

}  // namespace rr
