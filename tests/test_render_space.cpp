// Rendering space (loader/camera_reader.h): the loader translates the scene file's coordinates
// so that the camera is at the origin, in double, before rounding to float. A scene placed
// 10^6 units from the file's origin, where float spacing is 0.0625, then renders exactly as it
// does at the origin.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "loader/camera_reader.h"
#include "support/scene_testing.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

// Every kind of position a scene file gives (camera, look_at, sphere centre, quad corner, disk
// centre, polygon vertices, a mesh's translation, a transform matrix, point and spot lights),
// most at coordinates a float cannot hold at 10^6 (spacing 0.0625 there), each moved by
// `offset` along every axis.
std::string sceneAt(double offset, const std::string& meshFile) {
    auto coordinate = [offset](double x) {
        std::ostringstream s;
        s << std::fixed << x + offset;
        return s.str();
    };
    auto at = [offset](double x, double y, double z) {
        std::ostringstream s;
        s << std::fixed << "[" << x + offset << ", " << y + offset << ", " << z + offset << "]";
        return s.str();
    };
    return R"({
      "render": {"resolution": [20, 16], "max_depth": 4},
      "camera": {"position": )" +
           at(0, 1.2, 3.2) + R"(, "look_at": )" + at(0, 0.4, 0) + R"(, "fov": 50},
      "materials": {"white": {"type": "lambert", "albedo": 0.6},
                    "gloss": {"type": "cook_torrance", "reflectance": 0.9, "roughness": 0.2}},
      "shapes": [
        {"type": "quad", "corner": )" +
           at(-2, 0, 2) + R"(, "edge_u": [4, 0, 0], "edge_v": [0, 0, -4], "material": "white"},
        {"type": "sphere", "center": )" +
           at(-0.5, 0.4, 0) + R"(, "radius": 0.4, "material": "gloss"},
        {"type": "disk", "center": )" +
           at(0.9, 0.3, -0.5) + R"(, "normal": [0, 0, 1], "radius": 0.3, "material": "white"},
        {"type": "polygon", "vertices": [)" +
           at(-1.5, 0.1, -1) + ", " + at(-1.1, 0.1, -1) + ", " + at(-1.3, 0.6, -1) +
           R"(], "material": "white"},
        {"type": "mesh", "file": ")" +
           meshFile + R"(", "material": "gloss",
         "transform": {"scale": 0.2, "translate": )" +
           at(0.5, 0.3, 0.3) + R"(}},
        {"type": "sphere", "radius": 0.15, "material": "white",
         "transform": {"matrix": [1, 0, 0, )" +
           coordinate(-0.9) + ", 0, 1, 0, " + coordinate(0.15) + ", 0, 0, 1, " + coordinate(0.6) +
           R"(, 0, 0, 0, 1]}},
        {"type": "quad", "corner": )" +
           at(-0.3, 2, -0.3) + R"(, "edge_u": [0.6, 0, 0], "edge_v": [0, 0, 0.6],
         "emission": {"radiance": 15}}],
      "lights": [
        {"type": "point", "position": )" +
           at(1.1, 1.45, 0.9) + R"(, "intensity": 3},
        {"type": "spot", "position": )" +
           at(-1.05, 1.55, 0.95) + R"(, "look_at": )" + at(-0.45, 0.05, 0.1) +
           R"(, "intensity": 5, "cone_angle": 30}]
    })";
}

std::string writeTetrahedron() {
    const auto file = scratchDirectory() / "tetrahedron.ply";
    std::ofstream(file) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                           "property float y\nproperty float z\nelement face 4\n"
                           "property list uchar int vertex_indices\nend_header\n"
                           "0 1 0\n-1 -0.5 0.6\n1 -0.5 0.6\n0 -0.5 -1\n"
                           "3 0 1 2\n3 0 3 1\n3 0 2 3\n3 1 3 2\n";
    return file.string();
}

TEST(RenderSpace, TheCameraIsAtTheOriginAndPositionsAreRelativeToIt) {
    const Json camera = Json::parse(
        R"({"position": [1000000, 1000001.2, 1000003.2], "look_at": [1000000, 1000000.4, 1e6]})");
    ObjectReader reader(camera, "/camera");
    const CameraReading view = readCamera(reader);
    EXPECT_EQ(view.camera.position, Vec3(0.0f));
    EXPECT_EQ(view.camera.lookAt, Vec3(0.0f, -0.8f, -3.2f));
    // In float, 1000000.4 - 1000001.2 would be 1000000.375 - 1000001.1875 = -0.8125.
    EXPECT_EQ(view.worldToRender.point(Vec3d{999998.0, 1000000.0, 1000002.0}),
              Vec3(-2, -1.2f, -1.2f));
}

TEST(RenderSpace, ASceneFarFromTheOriginRendersAsItDoesAtTheOrigin) {
    const std::string mesh = writeTetrahedron();
    const TestRender atOrigin = renderScene(loadSceneText(sceneAt(0, mesh)), 16, 7);
    const TestRender far = renderScene(loadSceneText(sceneAt(1e6, mesh)), 16, 7);
    const Film& a = atOrigin.film;
    const Film& b = far.film;
    int differing = 0;
    double total = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            differing += !(a.mean(x, y) == b.mean(x, y));
            total += a.mean(x, y).r;
        }
    EXPECT_GT(total, 0.0);
    EXPECT_EQ(differing, 0);
}

}  // namespace
}  // namespace rr::test
