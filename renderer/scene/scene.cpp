#include "scene/scene.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "scene/lights/area_light.h"
#include "scene/material.h"

namespace rr {

namespace {

void throwOnEmbreeError(RTCDevice device, const char* what) {
    const RTCError err = rtcGetDeviceError(device);
    if (err != RTC_ERROR_NONE)
        throw std::runtime_error(std::string("Embree error during ") + what + " (code " +
                                 std::to_string(static_cast<int>(err)) + ")");
}

RTCRay toEmbree(const Ray& ray) {
    RTCRay r;
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.direction.x;
    r.dir_y = ray.direction.y;
    r.dir_z = ray.direction.z;
    r.tnear = 0.0f;
    r.tfar = ray.tMax;
    r.time = ray.time;
    r.mask = 0xffffffffu;
    r.id = 0;
    r.flags = 0;
    return r;
}

}  // namespace

Scene::~Scene() {
    if (rtcScene_) rtcReleaseScene(rtcScene_);
    if (device_) rtcReleaseDevice(device_);
}

namespace {
// Debian's Embree asserts (and aborts the process) on non-finite rays. None should arise from
// validated input, but a degenerate one (a zero-length shadow segment) must not kill a render.
bool isValid(const Ray& ray) {
    return isFinite(ray.origin) && isFinite(ray.direction);
}
}  // namespace

bool Scene::intersect(const Ray& ray, SurfaceHit* hit) const {
    if (!isValid(ray)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = toEmbree(ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtcScene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    const Shape* shape = shapes_[rh.hit.geomID].get();
    hit->distance = rh.ray.tfar;
    hit->time = ray.time;
    hit->shape = shape;
    shape->completeHit(ray, rh.hit, hit);
    return true;
}

bool Scene::occluded(const Ray& ray) const {
    if (!isValid(ray)) return true;  // a degenerate connection carries no light
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = toEmbree(ray);
    rtcOccluded1(rtcScene_, &context, &r);
    return r.tfar < 0;
}

SceneBuilder::SceneBuilder() : scene_(new Scene()) {
    scene_->device_ = rtcNewDevice(nullptr);
    if (!scene_->device_) throw std::runtime_error("cannot create an Embree device");
    scene_->rtcScene_ = rtcNewScene(scene_->device_);
}

const Material* SceneBuilder::addMaterial(std::unique_ptr<Material> material) {
    material->setIndex(static_cast<int>(scene_->materials_.size()));
    scene_->materials_.push_back(std::move(material));
    return scene_->materials_.back().get();
}

const Medium* SceneBuilder::addMedium(std::unique_ptr<Medium> medium) {
    scene_->media_.push_back(std::move(medium));
    return scene_->media_.back().get();
}

void SceneBuilder::setSceneMedium(const Medium* medium) {
    scene_->medium_ = medium;
}

void SceneBuilder::addShape(std::unique_ptr<Shape> shape, const Material* material,
                            const Rgb& emission, bool twoSidedEmission) {
    shape->setMaterial(material);
    if (!emission.isBlack()) {
        auto light = std::make_unique<AreaLight>(shape.get(), emission, twoSidedEmission);
        shape->setAreaLight(light.get());
        addLight(std::move(light));
    }
    scene_->shapes_.push_back(std::move(shape));
}

void SceneBuilder::addLight(std::unique_ptr<Light> light) {
    light->setIndex(static_cast<int>(scene_->lights_.size()));
    scene_->lights_.push_back(light.get());
    scene_->ownedLights_.push_back(std::move(light));
}

void SceneBuilder::setRenderOrigin(const Vec3d& origin) {
    scene_->renderOrigin_ = origin;
}

void SceneBuilder::setCamera(const CameraSettings& settings, int width, int height) {
    scene_->camera_ = std::make_unique<Camera>(settings, width, height);
}

std::unique_ptr<Scene> SceneBuilder::build(LightSelection selection) {
    Scene& s = *scene_;
    if (!s.camera_) throw std::logic_error("scene has no camera");
    for (size_t i = 0; i < s.shapes_.size(); ++i) {
        RTCGeometry g = s.shapes_[i]->createGeometry(s.device_);
        rtcAttachGeometryByID(s.rtcScene_, g, static_cast<unsigned>(i));
        rtcReleaseGeometry(g);
    }
    rtcSetSceneBuildQuality(s.rtcScene_, RTC_BUILD_QUALITY_HIGH);
    rtcCommitScene(s.rtcScene_);
    throwOnEmbreeError(s.device_, "scene build");

    // Infinite lights need the bounding sphere (shadow-ray targets, power) before the light
    // selector asks for power. A scene of lights only gets the unit sphere.
    Vec3 center(0.0f);
    float radius = 1;
    if (!s.shapes_.empty()) {
        RTCBounds b;
        rtcGetSceneBounds(s.rtcScene_, &b);
        const Vec3 lo(b.lower_x, b.lower_y, b.lower_z), hi(b.upper_x, b.upper_y, b.upper_z);
        center = (lo + hi) * 0.5f;
        radius = std::max(0.5f * length(hi - lo), 1e-6f);
    }
    for (const std::unique_ptr<Light>& owned : s.ownedLights_) {
        Light* light = owned.get();
        light->preprocess(center, radius);
        if (light->isInfinite()) s.infiniteLights_.push_back(light);
    }

    s.hasMedia_ = s.medium_ != nullptr;
    for (const std::unique_ptr<Shape>& shape : s.shapes_)
        s.hasMedia_ = s.hasMedia_ || shape->interiorMedium();
    s.lightSelector_ = makeLightSelector(selection, s.lights_);
    return std::move(scene_);
}

}  // namespace rr
