// Where a material or texture is evaluated: texture coordinates and position, for spatially
// varying parameters (checkerboards, gradients, image maps).
#pragma once

#include "math/vector.h"

namespace rr {

struct ShadingContext {
    Vec2 uv;
    Vec3 position;
};

}  // namespace rr
