// sin(πx) and cos(πx) together, in float, without libm: environment-map layouts turn every light
// sample's image point into a direction (a sine and cosine of the polar angle, and for lat-long
// maps of the azimuth), and at resampling's rates libm's sinf and cosf were 7 % of a render
// (issue 40). The argument is reduced exactly to r ∈ [−¼, ¼] quarter turns, where Taylor
// polynomials of degree 9 (sine) and 10 (cosine) are accurate to 2·10⁻⁹, below float's
// resolution; the result is within a few ulp of the correctly rounded one.
#pragma once

#include <cmath>

namespace rr {

struct SinCos {
    float sin, cos;
};

inline SinCos sinCosPi(float x) {
    // x = q/2 + r with q the nearest integer to 2x: x − q/2 is exact (q/2 is within ¼ of x).
    const float q = std::nearbyint(2 * x);
    const float r = x - 0.5f * q;
    const float a = r * 3.14159265358979f, a2 = a * a;
    const float s =
        a * (1 + a2 * (-1.0f / 6 + a2 * (1.0f / 120 + a2 * (-1.0f / 5040 + a2 * (1.0f / 362880)))));
    const float c =
        1 + a2 * (-0.5f + a2 * (1.0f / 24 +
                                a2 * (-1.0f / 720 + a2 * (1.0f / 40320 + a2 * (-1.0f / 3628800)))));
    switch (static_cast<long long>(q) & 3) {
        case 0:
            return {s, c};
        case 1:
            return {c, -s};
        case 2:
            return {-s, -c};
        default:
            return {-c, s};
    }
}

}  // namespace rr
