// The checkerboard pattern shared by the checker texture and the checker material: square
// (i, j) = (⌊u·nu⌋, ⌊v·nv⌋) of the texture-coordinate plane is "even" when i + j is even.
#pragma once

#include <cmath>

#include "math/vector.h"

namespace rr {

struct Checkerboard {
    int nu = 8, nv = 8;  // squares per unit of u and of v

    bool isEven(Vec2 uv) const {
        // In double, the square indices are exact integers for any float uv.
        const double squares = std::floor(double(uv.x) * nu) + std::floor(double(uv.y) * nv);
        return std::fmod(squares, 2.0) == 0;  // fmod keeps the sign: −1 is odd too
    }
};

}  // namespace rr
