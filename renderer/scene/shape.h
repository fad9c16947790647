// A shape is geometry Embree can intersect, plus what lights need from it: area and sampling.
// Shapes may translate linearly over scene time [0, 1] (motion blur); `offsetAt` gives the
// displacement at a time. Shapes are built in rendering space (loader/camera_reader.h; transforms
// applied at load).
#pragma once

#include <embree3/rtcore.h>

#include "math/vector.h"
#include "scene/surface_hit.h"

namespace rr {

class Material;
class AreaLight;
class Medium;

// A point on a shape chosen by a light-sampling strategy; `pdf` is per unit solid angle as
// seen from the reference point.
struct ShapeSample {
    Vec3 position;
    Vec3 normal;
    float pdf = 0;
    float errorScale = 0;  // as SurfaceHit::errorScale
};

class Shape {
  public:
    virtual ~Shape() = default;

    // The Embree geometry (committed), with two time steps when the shape moves.
    virtual RTCGeometry createGeometry(RTCDevice device) const = 0;
    // Fills position, normals and uv from Embree's hit record (ray distance `t`).
    virtual void completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const = 0;

    virtual float area() const = 0;
    // Uniform sample by area at time 0: position, normal and error scale (pdf left unset;
    // the density is 1/area).
    virtual ShapeSample sampleArea(Vec2 u) const = 0;

    // Samples a point visible-side-agnostically with a solid-angle density from `reference`.
    // The default converts uniform area sampling; shapes with better strategies override both
    // this and directionPdf consistently.
    virtual bool sampleDirection(const Vec3& reference, Vec2 u, float time, ShapeSample* out) const;
    // The default's sampling: uniform by area, the density converted to solid angle.
    bool sampleDirectionByArea(const Vec3& reference, Vec2 u, float time, ShapeSample* out) const;
    // Solid-angle density with which sampleDirection would produce `hit` from `reference`.
    virtual float directionPdf(const Vec3& reference, const SurfaceHit& hit) const;
    // The inverse of sampleDirection: the u for which sampleDirection(reference, u, …) yields
    // the point `point` of this shape. False by default: for shapes whose sampling has no
    // implemented inverse (triangle meshes: area sampling would need the triangle the point
    // lies on; polygons: Arvo's spherical-triangle sampling), and for moving shapes, whose
    // samples depend on the time, which the inverse is not given (it would have to guess it).
    virtual bool invertSampleDirection(const Vec3& /*reference*/, const Vec3& /*point*/,
                                       Vec2* /*u*/) const {
        return false;
    }
    // Whether invertSampleDirection is implemented for this shape (and it does not move).
    virtual bool invertsSamples() const { return false; }

    void setMotion(const Vec3& translation) { motion_ = translation; }
    bool hasMotion() const { return !(motion_ == Vec3(0.0f)); }
    Vec3 offsetAt(float time) const { return motion_ * time; }
    // Magnitude of the motion's contribution to positions, for error scales.
    float motionScale() const { return maxAbsComponent(motion_); }

    void setMaterial(const Material* m) { material_ = m; }
    const Material* material() const { return material_; }
    void setAreaLight(const AreaLight* l) { areaLight_ = l; }
    const AreaLight* areaLight() const { return areaLight_; }
    // The medium filling the shape's inside, the side opposite its geometric normal (closed
    // shapes with outward normals); nullptr: the shape does not change the medium.
    void setInteriorMedium(const Medium* m) { interiorMedium_ = m; }
    const Medium* interiorMedium() const { return interiorMedium_; }
    // An index-matched boundary of a medium: no material, so rays pass through it unchanged
    // and only the medium changes.
    bool isMediumBoundary() const { return !material_ && interiorMedium_; }

  protected:
    // Uploads `count` vertices (one or two time steps) into an Embree vertex buffer.
    void setVertexBuffers(RTCGeometry geometry, const Vec3* vertices, size_t count) const;

  private:
    Vec3 motion_;
    const Material* material_ = nullptr;
    const AreaLight* areaLight_ = nullptr;
    const Medium* interiorMedium_ = nullptr;
};

// Converts an area density at `position` (normal `normal`) seen from `reference` to solid angle.
float areaToSolidAngle(float areaPdf, const Vec3& reference, const Vec3& position,
                       const Vec3& normal);

}  // namespace rr
