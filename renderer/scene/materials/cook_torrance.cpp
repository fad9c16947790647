#include "scene/materials/cook_torrance.h"

#include "scene/materials/microfacet.h"

namespace rr {

using namespace microfacet;

float beckmannD(const Vec3& h, float alpha) {
    if (h.z <= 0) return 0;
    const float cos2 = h.z * h.z;
    const float tan2 = sin2Theta(h) / cos2;
    const float alpha2 = alpha * alpha;
    const float e = std::exp(-tan2 / alpha2);
    // Where the exponential underflows D is zero; testing it first avoids 0/0 when cos⁴ θh
    // underflows too.
    if (e == 0) return 0;
    return e / (kPi * alpha2 * cos2 * cos2);
}

float beckmannSmithG1(const Vec3& w, const Vec3& h, float alpha) {
    if (dot(w, h) <= 0) return 0;  // χ⁺(w·h / w·n): the facet faces away from w
    const float sinTheta = std::sqrt(sin2Theta(w));
    if (sinTheta == 0) return 1;
    const float a = w.z / (alpha * sinTheta);  // 1 / (α tan θ)
    // Walter et al. 2007 §5.1: 2 / (1 + erf(a) + exp(−a²) / (a √π)).
    return 2.0f / (1.0f + std::erf(a) + std::exp(-a * a) / (a * std::sqrt(kPi)));
}

Vec3 BeckmannDistribution::sampleHalfVector(Vec2 u, float alpha) {
    // Walter et al. 2007 §5.1: tan² θh = −α² ln(1 − u1), φh = 2π u2.
    const float tan2 = -alpha * alpha * std::log1p(-u.x);
    const float cosTheta = 1.0f / std::sqrt(1.0f + tan2);
    const float sinTheta = std::sqrt(tan2) * cosTheta;
    return sphericalDirection(sinTheta, cosTheta, kTwoPi * u.y);
}

}  // namespace rr
