// Fuzz target: scene documents. The input is the scene file's text, loaded and validated as
// `renderer render` does, then rendered at 1×1 (fuzz_support.h says what counts as a finding).
// Seeds: tests/fuzz/corpus/scene and every scene in configs/ (make fuzz passes both).
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    rr::fuzz::renderOnePixel(rr::fuzz::writeInput("scene.json", data, size));
    return 0;
}
