#include "loader/camera_reader.h"

namespace rr {

CameraReading readCamera(ObjectReader& j) {
    CameraSettings c;
    const std::string type = j.getChoice("type", {"pinhole", "thin_lens"}, "pinhole");
    const Vec3d position = j.getPoint("position");
    const Transform worldToRender = Transform::translate(-position);
    c.position = Vec3(0.0f);
    c.lookAt = worldToRender.point(j.getPoint("look_at"));
    c.up = j.getVec3("up", Vec3(0, 1, 0));
    c.verticalFovDegrees = j.getFloat("fov", 40.0f, Range::open(0, 180));
    const Vec3 forward = c.lookAt - c.position;
    if (!(length(forward) > 0)) j.fail("look_at", "must differ from the camera position");
    if (!(length(c.up) > 0)) j.fail("up", "expected a non-zero vector");
    c.up = normalize(c.up);  // only its direction matters: a tiny up is as good as a unit one
    if (!(length(cross(normalize(forward), c.up)) > 1e-4f))
        j.fail("up", "must not be parallel to the viewing direction");
    if (type == "thin_lens") {
        c.apertureRadius = j.getFloat("aperture_radius", Range::positive());
        c.focusDistance = j.getFloat("focus_distance", Range::positive());
    }
    c.samplePixelArea = j.getChoice("pixel_sample", {"area", "centre"}, "area") == "area";
    if (j.has("shutter")) {
        const auto s = j.getNumbers("shutter", 2, Range::unit());
        if (s[0] > s[1]) j.fail("shutter", "expected [open, close] with open <= close");
        c.shutterOpen = static_cast<float>(s[0]);
        c.shutterClose = static_cast<float>(s[1]);
    }
    j.finish();
    return {c, position, worldToRender};
}

}  // namespace rr
