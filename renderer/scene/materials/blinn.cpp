#include "scene/materials/blinn.h"

namespace rr {

using namespace microfacet;

float BlinnPhongDistribution::D(const Vec3& h, float exponent) {
    return (exponent + 2.0f) * (0.5f * kInvPi) * cosPower(h, exponent);
}

Vec3 BlinnPhongDistribution::sampleHalfVector(Vec2 u, float exponent) {
    // D(h) cos θh = (e + 2)/(2π) cos^(e+1) θh: cos θh = u^(1/(e+2)), uniform azimuth.
    float sinTheta;
    const float cosTheta = sampleCosPower(u.x, exponent + 2.0f, &sinTheta);
    return sphericalDirection(sinTheta, cosTheta, kTwoPi * u.y);
}

}  // namespace rr
