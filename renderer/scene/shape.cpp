#include "scene/shape.h"

#include <cmath>
#include <vector>

namespace rr {

float areaToSolidAngle(float areaPdf, const Vec3& reference, const Vec3& position,
                       const Vec3& normal) {
    const Vec3 d = position - reference;
    const float dist2 = lengthSquared(d);
    const float cosTheta = std::abs(dot(normal, d)) / std::sqrt(dist2);
    return cosTheta > 0 ? areaPdf * dist2 / cosTheta : 0.0f;
}

bool Shape::sampleDirection(const Vec3& reference, Vec2 u, float time, ShapeSample* out) const {
    return sampleDirectionByArea(reference, u, time, out);
}

bool Shape::sampleDirectionByArea(const Vec3& reference, Vec2 u, float time,
                                  ShapeSample* out) const {
    *out = sampleArea(u);
    out->position += offsetAt(time);
    out->errorScale += motionScale();
    out->pdf = areaToSolidAngle(1.0f / area(), reference, out->position, out->normal);
    return out->pdf > 0 && std::isfinite(out->pdf);
}

float Shape::directionPdf(const Vec3& reference, const SurfaceHit& hit) const {
    return areaToSolidAngle(1.0f / area(), reference, hit.position, hit.geometricNormal);
}

void Shape::setVertexBuffers(RTCGeometry geometry, const Vec3* vertices, size_t count) const {
    const unsigned steps = hasMotion() ? 2 : 1;
    rtcSetGeometryTimeStepCount(geometry, steps);
    for (unsigned step = 0; step < steps; ++step) {
        auto* buffer = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, step, RTC_FORMAT_FLOAT3, 3 * sizeof(float), count));
        const Vec3 offset = offsetAt(static_cast<float>(step));
        for (size_t i = 0; i < count; ++i) {
            const Vec3 v = vertices[i] + offset;
            buffer[3 * i + 0] = v.x;
            buffer[3 * i + 1] = v.y;
            buffer[3 * i + 2] = v.z;
        }
    }
}

}  // namespace rr
