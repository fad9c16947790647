// A small scene document whose one asset is `file` (a name in the scene's directory): a mesh
// (.ply, .obj; smooth normals) lit by a point light, or a lat-long environment map (.exr,
// .hdr) lighting a diffuse sphere, seen by a camera 3 units away. The damaged-asset tests and
// the fuzz targets render their files through it. Header-only: the fuzz build has no gtest.
#pragma once

#include <string>

namespace rr::test {

inline std::string sceneUsingAsset(const std::string& file) {
    const bool mesh = file.ends_with(".ply") || file.ends_with(".obj");
    const std::string common = R"({
  "camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 60 },
  "materials": { "m": { "type": "lambert", "albedo": 0.5 } },
)";
    if (mesh)
        return common + R"(  "shapes": [ { "type": "mesh", "file": ")" + file +
               R"(", "material": "m", "normals": "smooth" } ],
  "lights": [ { "type": "point", "position": [0, 2, 2], "intensity": 5 } ] })";
    return common +
           R"(  "shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "m" } ],
  "lights": [ { "type": "environment", "file": ")" +
           file + R"(", "layout": "latlong" } ] })";
}

}  // namespace rr::test
