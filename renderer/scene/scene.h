// A renderable scene: camera, shapes with materials, lights, and the Embree acceleration
// structure. Built once by SceneBuilder, then immutable and shared by all render threads.
#pragma once

#include <embree3/rtcore.h>

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "scene/camera.h"
#include "scene/light.h"
#include "scene/light_selector.h"
#include "scene/material.h"
#include "scene/medium.h"
#include "scene/shape.h"
#include "scene/surface_hit.h"

namespace rr {

class AreaLight;

class Scene {
  public:
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    bool intersect(const Ray& ray, SurfaceHit* hit) const;
    bool occluded(const Ray& ray) const;

    const Camera& camera() const { return *camera_; }
    // Where rendering space's origin is in the scene file's coordinates: the camera's position
    // (loader/camera_reader.h). Everything in the scene is in rendering space; a point the file
    // names is at `point - renderOrigin()` here.
    const Vec3d& renderOrigin() const { return renderOrigin_; }
    std::span<const Light* const> lights() const { return lights_; }
    // The lights that rays escaping the scene see (environment maps).
    std::span<const Light* const> infiniteLights() const { return infiniteLights_; }
    const LightSelector& lightSelector() const { return *lightSelector_; }
    // The shapes; index = Embree geometry id.
    std::span<const std::unique_ptr<Shape>> shapes() const { return shapes_; }
    // The materials of the scene's shapes.
    std::span<const std::unique_ptr<Material>> materials() const { return materials_; }
    // The medium filling the scene outside the shapes that have an interior medium (nullptr:
    // vacuum). It fills all space, so it also attenuates infinite lights.
    const Medium* medium() const { return medium_; }
    // Whether there are participating media: the scene's or a shape's interior.
    bool hasMedia() const { return hasMedia_; }

  private:
    friend class SceneBuilder;
    Scene() = default;

    std::unique_ptr<Camera> camera_;
    Vec3d renderOrigin_;
    std::vector<std::unique_ptr<Material>> materials_;
    std::vector<std::unique_ptr<Medium>> media_;
    const Medium* medium_ = nullptr;
    std::vector<std::unique_ptr<Shape>> shapes_;  // index = Embree geometry id
    std::vector<std::unique_ptr<Light>> ownedLights_;
    std::vector<const Light*> lights_;
    std::vector<const Light*> infiniteLights_;
    std::unique_ptr<LightSelector> lightSelector_;
    bool hasMedia_ = false;
    RTCDevice device_ = nullptr;
    RTCScene rtcScene_ = nullptr;
};

class SceneBuilder {
  public:
    SceneBuilder();

    // Materials are owned by the scene; the returned pointer stays valid.
    const Material* addMaterial(std::unique_ptr<Material> material);
    // Media are owned by the scene too: the scene's medium and shapes' interiors point to them.
    const Medium* addMedium(std::unique_ptr<Medium> medium);
    void setSceneMedium(const Medium* medium);
    // Adds a shape with its material (and its interior medium, if set on the shape); a
    // non-black `emission` makes it an area light.
    void addShape(std::unique_ptr<Shape> shape, const Material* material, const Rgb& emission,
                  bool twoSidedEmission);
    void addLight(std::unique_ptr<Light> light);
    void setCamera(const CameraSettings& settings, int width, int height);
    void setRenderOrigin(const Vec3d& origin);

    // Builds the acceleration structure. Throws std::runtime_error on Embree failure.
    std::unique_ptr<Scene> build(LightSelection selection);

  private:
    std::unique_ptr<Scene> scene_;
};

}  // namespace rr
