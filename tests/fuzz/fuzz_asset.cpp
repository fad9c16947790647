// Fuzz targets for the asset readers, one per format: the input is a file (`input.<format>`)
// that a fixed scene uses as its mesh or environment map, rendered at 1×1 (fuzz_support.h says
// what counts as a finding). EXR inputs are also read as the metrics tool reads images.
// FUZZ_FORMAT is "ply", "obj", "exr" or "hdr" (tests/fuzz/CMakeLists.txt).
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "io/exr_io.h"

namespace {

constexpr std::string_view kFormat = FUZZ_FORMAT;
constexpr bool kIsMesh = kFormat == "ply" || kFormat == "obj";

// A camera looking at the origin from 3 units away; the mesh (placed as it is in its file) or
// the environment map is the scene's only content worth the name.
constexpr std::string_view kCamera =
    R"("camera": { "position": [0, 0, 3], "look_at": [0, 0, 0], "fov": 60 },)";

std::string meshScene() {
    return std::string("{") + std::string(kCamera) + R"(
  "materials": { "m": { "type": "lambert", "albedo": 0.5 } },
  "shapes": [ { "type": "mesh", "file": "input.)" +
           std::string(kFormat) + R"(", "material": "m", "normals": "smooth" } ],
  "lights": [ { "type": "point", "position": [0, 2, 2], "intensity": 5 } ] })";
}

std::string environmentScene() {
    return std::string("{") + std::string(kCamera) + R"(
  "materials": { "m": { "type": "lambert", "albedo": 0.5 } },
  "shapes": [ { "type": "sphere", "center": [0, 0, 0], "radius": 0.5, "material": "m" } ],
  "lights": [ { "type": "environment", "file": "input.)" +
           std::string(kFormat) + R"(", "layout": "latlong" } ] })";
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string name = "input." + std::string(kFormat);
    const auto input = rr::fuzz::writeInput(name, data, size);
    if constexpr (kFormat == "exr") {
        try {
            (void)rr::readExr(input);
        } catch (const std::runtime_error&) {  // the metrics tool reports it: not a finding
        }
    }
    const auto scene =
        rr::fuzz::writeFixedFile("scene.json", kIsMesh ? meshScene() : environmentScene());
    rr::fuzz::renderOnePixel(scene);
    return 0;
}
