#include "loader/camera_reader.h"

namespace rr {

namespace {

const CameraSettings kDefaults;

const KeyTable kCameraKeys{
    "camera",
    "pinhole or thin lens, field of view, shutter interval",
    {key("type").choice({"pinhole", "thin_lens"}).byDefault("pinhole").means("the camera model"),
     key("position").vector().means("eye (pinhole) or lens centre"),
     key("look_at").vector().means("a point on the optical axis; must differ from `position`"),
     key("up")
         .vector()
         .byDefault({kDefaults.up.x, kDefaults.up.y, kDefaults.up.z})
         .means("up direction (any non-zero length); not parallel to the view direction"),
     key("fov")
         .number(Range::open(0, 180))
         .byDefault(kDefaults.verticalFovDegrees)
         .means("vertical field of view in degrees"),
     key("aperture_radius")
         .number(Range::positive())
         .defaultSays("required for `thin_lens`")
         .means("lens radius"),
     key("focus_distance")
         .number(Range::positive())
         .defaultSays("required for `thin_lens`")
         .means("distance along the axis of the plane in focus"),
     key("shutter")
         .numbers(2, Range::unit())
         .byDefault({kDefaults.shutterOpen, kDefaults.shutterClose})
         .means("[open, close], open ≤ close: the interval of scene time the exposure covers; "
                "open = close: no motion blur, moving shapes frozen at that instant"),
     key("pixel_sample")
         .choice({"area", "centre"})
         .byDefault("area")
         .means("camera rays cross their pixel uniformly over its area (the `film_position` "
                "decision), or through its centre (a pixel estimator's error alone: two-stage "
                "fig. 8)")}};

}  // namespace

const KeyTable& cameraKeys() {
    return kCameraKeys;
}

CameraReading readCamera(ObjectReader& j) {
    j.addKeys(kCameraKeys);
    CameraSettings c;
    const std::string type = j.choice("type");
    const Vec3d position = j.point("position");
    const Transform worldToRender = Transform::translate(-position);
    c.position = Vec3(0.0f);
    c.lookAt = worldToRender.point(j.point("look_at"));
    c.up = j.vector("up");
    c.verticalFovDegrees = j.real("fov");
    const Vec3 forward = c.lookAt - c.position;
    if (!(length(forward) > 0)) j.fail("look_at", "must differ from the camera position");
    if (!(length(c.up) > 0)) j.fail("up", "expected a non-zero vector");
    c.up = normalize(c.up);  // only its direction matters: a tiny up is as good as a unit one
    if (!(length(cross(normalize(forward), c.up)) > 1e-4f))
        j.fail("up", "must not be parallel to the viewing direction");
    if (type == "thin_lens") {
        c.apertureRadius = j.real("aperture_radius");
        c.focusDistance = j.real("focus_distance");
    }
    c.samplePixelArea = j.choice("pixel_sample") == "area";
    const auto s = j.numbers("shutter");
    if (s[0] > s[1]) j.fail("shutter", "expected [open, close] with open <= close");
    c.shutterOpen = static_cast<float>(s[0]);
    c.shutterClose = static_cast<float>(s[1]);
    j.finish();
    return {c, position, worldToRender};
}

}  // namespace rr
