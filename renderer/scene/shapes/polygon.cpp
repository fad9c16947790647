#include "scene/shapes/polygon.h"

#include <algorithm>
#include <cmath>

#include "math/dvec3.h"
#include "sampling/spherical_triangle.h"
#include "sampling/warps.h"

namespace rr {

namespace {

// The polygon's plane in double precision: the vertices relative to their mean, the unit
// normal (Newell's area vector, right-hand rule on the vertex order), area and size.
struct Plane {
    std::vector<DVec3> p;  // vertex − mean
    DVec3 mean, normal;
    double area = 0, size = 0;
};

Plane fitPlane(std::span<const Vec3> vertices) {
    Plane plane;
    const double n = double(vertices.size());
    for (const Vec3& v : vertices)
        plane.mean = plane.mean + DVec3(v) / n;
    for (const Vec3& v : vertices) {
        plane.p.push_back(DVec3(v) - plane.mean);
        plane.size = std::max(plane.size, length(plane.p.back()));
    }
    DVec3 sum;
    for (size_t i = 0; i < plane.p.size(); ++i)
        sum = sum + cross(plane.p[i], plane.p[(i + 1) % plane.p.size()]);
    const double twiceArea = length(sum);
    plane.area = twiceArea / 2;
    if (twiceArea > 0) plane.normal = sum / twiceArea;
    return plane;
}

}  // namespace

std::optional<PolygonProblem> checkConvexPolygon(std::span<const Vec3> vertices) {
    const int n = static_cast<int>(vertices.size());
    if (n < 3) return PolygonProblem{-1, "a polygon needs at least 3 vertices"};
    if (n > Polygon::kMaxVertices)
        return PolygonProblem{
            -1, "a polygon has at most " + std::to_string(Polygon::kMaxVertices) + " vertices"};
    const Plane plane = fitPlane(vertices);
    const double r = plane.size;
    for (int i = 0; i < n; ++i)
        if (length(plane.p[(i + 1) % n] - plane.p[i]) <= 1e-6 * r)
            return PolygonProblem{(i + 1) % n, "repeats the previous vertex"};
    if (!(plane.area > 1e-6 * r * r)) return PolygonProblem{-1, "the polygon has zero area"};
    int worst = 0;
    for (int i = 1; i < n; ++i)
        if (std::abs(dot(plane.p[i], plane.normal)) > std::abs(dot(plane.p[worst], plane.normal)))
            worst = i;
    const double offPlane = std::abs(dot(plane.p[worst], plane.normal));
    if (offPlane > 1e-4 * r)
        return PolygonProblem{worst, "is the farthest off the polygon's plane, by " +
                                         std::to_string(offPlane) +
                                         " (more than 1e-4 of the polygon's size)"};
    // Turning angle at each vertex, signed about the normal: all ≥ 0 for a convex polygon,
    // and summing to 2π when the boundary winds around once (a pentagram turns by 4π).
    double totalTurn = 0;
    for (int i = 0; i < n; ++i) {
        const DVec3 in = plane.p[i] - plane.p[(i + n - 1) % n];
        const DVec3 out = plane.p[(i + 1) % n] - plane.p[i];
        const double turn = std::atan2(dot(cross(in, out), plane.normal), dot(in, out));
        if (turn < -1e-5) return PolygonProblem{i, "makes the polygon non-convex"};
        if (turn > M_PI - 1e-5) return PolygonProblem{i, "folds the boundary back on itself"};
        totalTurn += turn;
    }
    if (std::abs(totalTurn - 2 * M_PI) > 1e-3)
        return PolygonProblem{-1, "the boundary winds around more than once (self-intersecting)"};
    return std::nullopt;
}

Polygon::Polygon(std::span<const Vec3> vertices, PolygonSampling sampling) : sampling_(sampling) {
    const Plane plane = fitPlane(vertices);
    normal_ = normalize(plane.normal.toFloat());
    for (const DVec3& p : plane.p)  // projected onto the plane
        vertices_.push_back((plane.mean + p - plane.normal * dot(p, plane.normal)).toFloat());
    const Vec3& v0 = vertices_[0];
    std::vector<float> areas;
    for (size_t k = 1; k + 1 < vertices_.size(); ++k) {
        areas.push_back(0.5f * length(cross(vertices_[k] - v0, vertices_[k + 1] - v0)));
        area_ += areas.back();
    }
    fanByArea_ = Distribution1D(areas);

    const Vec3 u = normalize(vertices_[1] - v0), v = cross(normal_, u);
    float uMin = 0, uMax = 0, vMin = 0, vMax = 0;
    for (const Vec3& p : vertices_) {
        uMin = std::min(uMin, dot(p - v0, u));
        uMax = std::max(uMax, dot(p - v0, u));
        vMin = std::min(vMin, dot(p - v0, v));
        vMax = std::max(vMax, dot(p - v0, v));
        errorScale_ = std::max(errorScale_, maxAbsComponent(p));
    }
    uvOrigin_ = v0 + u * uMin + v * vMin;
    uAxis_ = u / (uMax - uMin);
    vAxis_ = v / (vMax - vMin);
}

RTCGeometry Polygon::createGeometry(RTCDevice device) const {
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    setVertexBuffers(g, vertices_.data(), vertices_.size());
    const size_t triangles = vertices_.size() - 2;
    auto* index = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
    for (unsigned k = 0; k < triangles; ++k) {
        index[3 * k + 0] = 0;
        index[3 * k + 1] = k + 1;
        index[3 * k + 2] = k + 2;
    }
    rtcCommitGeometry(g);
    return g;
}

void Polygon::completeHit(const Ray& ray, const RTCHit& hit, SurfaceHit* out) const {
    // Interpolated from the fan triangle's vertices with Embree's barycentrics, so the error is
    // relative to the polygon's coordinates, not to the ray origin's distance.
    const Vec3 offset = offsetAt(ray.time);
    const Vec3 &p0 = vertices_[0], &p1 = vertices_[hit.primID + 1], &p2 = vertices_[hit.primID + 2];
    const Vec3 p = p0 * (1 - hit.u - hit.v) + p1 * hit.u + p2 * hit.v;
    out->position = p + offset;
    out->errorScale = errorScale_ + motionScale();
    out->geometricNormal = normal_;
    out->shadingNormal = normal_;
    out->uv =
        Vec2(clamp(dot(p - uvOrigin_, uAxis_), 0, 1), clamp(dot(p - uvOrigin_, vAxis_), 0, 1));
}

ShapeSample Polygon::sampleArea(Vec2 u) const {
    float uRemapped;
    const int k = fanByArea_.sample(u.x, nullptr, &uRemapped) + 1;
    const Vec2 b = squareToUniformTriangle(Vec2(uRemapped, u.y));
    ShapeSample s;
    s.position = vertices_[0] * b.x + vertices_[k] * b.y + vertices_[k + 1] * (1 - b.x - b.y);
    s.normal = normal_;
    s.errorScale = errorScale_;
    return s;
}

// The spherical areas of the fan triangles seen from `reference`, at index k ≥ 2, and their sum;
// each triangle's sampler is made when first drawn from (a sample needs one, its pdf none).
struct Polygon::FanView {
    const Polygon* polygon = nullptr;
    Vec3 reference, offset;
    double total = 0;
    std::array<double, kMaxVertices> areas;
    std::array<DVec3, kMaxVertices> directions;  // unit, from the reference to each vertex
    std::array<bool, kMaxVertices> hasSampler;
    std::array<SphericalTriangleSampler, kMaxVertices> samplers;

    const SphericalTriangleSampler& sampler(size_t k) {
        if (!hasSampler[k]) {
            samplers[k] =
                SphericalTriangleSampler(directions[0], directions[k - 1], directions[k], areas[k]);
            hasSampler[k] = true;
        }
        return samplers[k];
    }
};

Polygon::FanView& Polygon::fanView(const Vec3& reference, const Vec3& offset) const {
    // A view is a pure function of its key, so keeping views changes no result: images stay
    // independent of threads and of the order of their work.
    constexpr size_t kViews = 4;
    thread_local std::array<FanView, kViews> views;
    thread_local size_t oldest = 0;
    for (FanView& view : views)
        if (view.polygon == this && view.reference == reference && view.offset == offset)
            return view;
    FanView& view = views[oldest];
    oldest = (oldest + 1) % kViews;
    view.polygon = this;
    view.reference = reference;
    view.offset = offset;
    const DVec3 r(reference);
    for (size_t k = 0; k < vertices_.size(); ++k)
        view.directions[k] = normalize(DVec3(vertices_[k] + offset) - r);
    view.total = 0;
    for (size_t k = 2; k < vertices_.size(); ++k) {
        view.areas[k] =
            sphericalTriangleArea(view.directions[0], view.directions[k - 1], view.directions[k]);
        view.total += view.areas[k];
        view.hasSampler[k] = false;
    }
    return view;
}

double Polygon::solidAngle(const Vec3& reference, const Vec3& offset) const {
    return fanView(reference, offset).total;
}

bool Polygon::sampleDirection(const Vec3& reference, Vec2 u, float time, ShapeSample* out) const {
    if (sampling_ == PolygonSampling::Area) return sampleDirectionByArea(reference, u, time, out);
    const Vec3 offset = offsetAt(time);
    // The view is the thread's: it stays valid until this thread asks for another view.
    FanView& view = fanView(reference, offset);
    const double total = view.total;
    if (!(total >= kMinSolidAngle)) return sampleDirectionByArea(reference, u, time, out);
    // The fan triangles project onto the sphere of directions without overlap (the polygon is
    // convex and planar): pick one with probability ∝ its solid angle, reusing u.x.
    const DVec3 r(reference);
    const double target = double(u.x) * total;
    double before = 0;
    for (size_t k = 2; k < vertices_.size(); ++k) {
        const double area = view.areas[k];
        if (before + area <= target && k + 1 < vertices_.size()) {
            before += area;
            continue;
        }
        if (!(area > 0)) return false;  // a degenerate last triangle, reached by rounding
        const float remapped = float(std::clamp((target - before) / area, 0.0, 1.0));
        const DVec3 w = view.sampler(k).sample(Vec2(std::min(remapped, kOneMinusEpsilon), u.y));
        // Where the direction meets the polygon's plane.
        const DVec3 n(normal_);
        const double t = dot(DVec3(vertices_[0] + offset) - r, n) / dot(w, n);
        if (!(t > 0)) return false;
        out->position = (r + w * t).toFloat();
        out->normal = normal_;
        out->pdf = float(1 / total);
        // The point is computed along the ray from the reference: its error scales with both.
        out->errorScale = errorScale_ + motionScale() + maxAbsComponent(reference) + float(t);
        return true;
    }
    return false;
}

float Polygon::directionPdf(const Vec3& reference, const SurfaceHit& hit) const {
    if (sampling_ == PolygonSampling::Area) return Shape::directionPdf(reference, hit);
    const double total = solidAngle(reference, offsetAt(hit.time));
    if (!(total >= kMinSolidAngle)) return Shape::directionPdf(reference, hit);
    return float(1 / total);
}

}  // namespace rr
