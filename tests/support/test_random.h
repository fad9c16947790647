// Test-side random numbers from the renderer's own counter-based generator: coordinate `dim`
// of sample `i` of stream `seed`, reproducible and independent of evaluation order.
#pragma once

#include <cstdint>

#include "math/vector.h"
#include "sampling/hash.h"

namespace rr::test {

inline float uniform(uint64_t seed, uint64_t i, uint64_t dim = 0) {
    return toUnitFloat(pcgOutput(hashKeys(seed, i, dim)));
}
inline Vec2 uniform2(uint64_t seed, uint64_t i) {
    return {uniform(seed, i, 0), uniform(seed, i, 1)};
}

}  // namespace rr::test
