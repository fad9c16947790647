// Fuzz targets for the asset readers, one per format: the input is a file (`input.<format>`)
// that a fixed scene (support/asset_scene.h) uses as its mesh or environment map, rendered at 1×1
// (fuzz_support.h says what counts as a finding). EXR inputs are also read as the metrics tool
// reads images. FUZZ_FORMAT is "ply", "obj", "exr" or "hdr" (tests/fuzz/CMakeLists.txt).
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_support.h"
#include "io/exr_io.h"
#include "support/asset_scene.h"

namespace {

constexpr std::string_view kFormat = FUZZ_FORMAT;

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
    const auto scene = rr::fuzz::writeFixedFile("scene.json", rr::test::sceneUsingAsset(name));
    rr::fuzz::renderOnePixel(scene);
    return 0;
}
