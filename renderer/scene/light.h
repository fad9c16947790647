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
// What only some estimators ask of a light is a capability it may also implement
// (scene/light_stand_in.h, scene/invertible_light.h).
#pragma once

#include <cstdint>
#include <span>

#include "math/rgb.h"
#include "math/vector.h"
#include "scene/surface_hit.h"

namespace rr {

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

class Light;

// A light sample as next-event estimation draws it, in batches (ShadingPoint::sampleLights):
// the light chosen, its sample, and the density of both (selection × point, per solid angle);
// `drawn` false when none was drawn.
struct LightDraw {
    LightSample sample;
    float pdf = 0;
    const Light* light = nullptr;
    bool drawn = false;
};

class Light {
  public:
    virtual ~Light() = default;

    virtual bool sample(const LightReference& reference, Vec2 u, float time,
                        LightSample* out) const = 0;
    // sample() for each of several coordinates at once: out[i] and drawn[i] as sample() with
    // u[i] gives them. Lights whose sampling reads large tables overlap the draws' cache misses
    // (resampling draws many candidates per shading point).
    virtual void sampleMany(const LightReference& reference, std::span<const Vec2> u, float time,
                            LightSample* out, bool* drawn) const {
        for (size_t i = 0; i < u.size(); ++i)
            drawn[i] = sample(reference, u[i], time, &out[i]);
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
    // Called once the scene is built, before power() is used: infinite lights need the
    // bounding sphere of the scene for their shadow-ray targets and their power.
    virtual void preprocess(const Vec3& /*sceneCenter*/, float /*sceneRadius*/) {}

    // Index in the scene's light list; set by the scene.
    int index() const { return index_; }
    void setIndex(int i) { index_ = i; }

  private:
    int index_ = -1;
};

}  // namespace rr
