// The normalised cosine-power lobe around a unit axis: density (n + 1)/(2π)·cos^n α over the
// directions with cos α > 0, α the angle to the axis (Lafortune & Willems 1994, §3: sampling
// the modified Phong lobe). Phong's specular lobe and Lafortune's generalised lobes both use it.
// Sharp lobes (n = 10⁴ and more) live where cos α rounds to 1 in float, so everything is
// computed from 1 − cos α, which stays accurate: 1 − cos α = |w − axis|²/2 for unit vectors.
#pragma once

#include <cmath>

#include "math/frame.h"
#include "math/vector.h"

namespace rr {

// 1 − cos α between unit vectors, without the cancellation of 1 − dot(w, axis).
inline double oneMinusCosine(const Vec3& w, const Vec3& axis) {
    const double dx = double(w.x) - axis.x, dy = double(w.y) - axis.y, dz = double(w.z) - axis.z;
    return 0.5 * (dx * dx + dy * dy + dz * dz);
}

// cos^n α from 1 − cos α; zero outside the lobe (cos α ≤ 0). 0^0 is taken as 0 there too, so
// an exponent-0 lobe is the hemisphere around the axis.
inline double cosinePower(double oneMinusCos, double exponent) {
    if (!(oneMinusCos < 1)) return 0;
    return std::exp(exponent * std::log1p(-oneMinusCos));
}

inline double cosinePowerPdf(double oneMinusCos, double exponent) {
    return (exponent + 1) / (2 * M_PI) * cosinePower(oneMinusCos, exponent);
}

// A direction of the lobe around `axis`: cos α = (1 − u.x)^(1/(n+1)) inverts the distribution
// of cos α, whose CDF is cos^(n+1) α (1 − u.x ∈ (0, 1], so the logarithm is finite and no
// draw lands exactly on the lobe's rim); φ = 2π u.y.
inline Vec3 sampleCosinePower(Vec2 u, double exponent, const Vec3& axis) {
    const double oneMinusCos = -std::expm1(std::log1p(-double(u.x)) / (exponent + 1));
    const double cosAlpha = 1 - oneMinusCos;
    const double sinAlpha = std::sqrt(std::max(0.0, oneMinusCos * (2 - oneMinusCos)));
    const double phi = 2 * M_PI * u.y;
    const Vec3 local(float(sinAlpha * std::cos(phi)), float(sinAlpha * std::sin(phi)),
                     float(cosAlpha));
    return normalize(Frame(axis).toWorld(local));
}

}  // namespace rr
