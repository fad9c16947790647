#include "techniques/tais/pixel_maps.h"

#include <algorithm>
#include <cmath>

namespace rr::tais {

namespace {

template <class Map>
void accumulateInto(std::optional<Map>& to, const std::optional<Map>& from, double scale) {
    if (to) to->accumulate(*from, scale);
}

template <class F>
void forEach(PixelMaps& maps, F&& f) {
    for (auto* m : {&maps.time, &maps.scatterDistance, &maps.bifurcation, &maps.lightSelection})
        if (*m) f(**m);
    for (auto* m : {&maps.lens, &maps.pointOnLight})
        if (*m) f(**m);
    for (InvertedMap2D& m : maps.scatterDirection)
        f(m);
}

// The per-entry constant of §3.3 step 2 for a map of `cells` entries: 1/n for preimage maps;
// for world maps `worldShare` of the (normalised) mass spread over the entries.
double floorFor(bool preimage, int cells, double worldShare) {
    return preimage ? preimageFloor(cells) : worldShare / cells;
}

template <class Temporary, class Map>
void addFinished(const std::optional<Temporary>& t, std::optional<Map>& map, bool preimage,
                 double worldShare) {
    if (t) t->addFinishedTo(*map, floorFor(preimage, t->cells(), worldShare));
}

// Creates the enabled maps of a PixelMaps or TemporaryMaps (same members, map types with the
// same constructors): 1-D maps from their cell count, 2-D maps from width and height.
template <class Maps>
void emplaceEnabled(Maps& m, const TaisSettings& s, int lightCount) {
    if (s.uses(MapKind::Time)) m.time.emplace(s.timeCells);
    if (s.uses(MapKind::ScatterDistance)) m.scatterDistance.emplace(s.scatterDistanceCells);
    if (s.uses(MapKind::Bifurcation)) m.bifurcation.emplace(2 * s.bifurcationVertices);
    if (s.uses(MapKind::LightSelection))
        m.lightSelection.emplace(s.lightSelectionVertices * lightCount);
    if (s.uses(MapKind::Lens)) m.lens.emplace(s.lensSize, s.lensSize);
    if (s.uses(MapKind::PointOnLight))
        m.pointOnLight.emplace(s.pointOnLightSize, s.pointOnLightSize);
    if (s.uses(MapKind::ScatterDirection))
        m.scatterDirection.assign(s.scatterDirectionBounces,
                                  typename decltype(m.scatterDirection)::value_type(
                                      s.scatterDirectionSize, s.scatterDirectionSize));
}

}  // namespace

Vec2 directionToMap(const Vec3& w) {
    float phi = std::atan2(w.y, w.x) * (0.5f / kPi);
    if (phi < 0) phi += 1;
    return {std::min(phi, kOneMinusEpsilon), std::clamp(0.5f * (1 - w.z), 0.0f, kOneMinusEpsilon)};
}

Vec3 mapToDirection(Vec2 p) {
    const float z = 1 - 2 * p.y;
    const float r = std::sqrt(std::max(0.0f, 1 - z * z));
    const float phi = 2 * kPi * p.x;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

PixelMaps PixelMaps::uniform(const TaisSettings& s, int lightCount) {
    PixelMaps m;
    emplaceEnabled(m, s, lightCount);
    m.lights = lightCount;
    m.normalize();
    return m;
}

void PixelMaps::accumulate(const PixelMaps& other, double scale) {
    accumulateInto(time, other.time, scale);
    accumulateInto(scatterDistance, other.scatterDistance, scale);
    accumulateInto(bifurcation, other.bifurcation, scale);
    accumulateInto(lightSelection, other.lightSelection, scale);
    accumulateInto(lens, other.lens, scale);
    accumulateInto(pointOnLight, other.pointOnLight, scale);
    for (size_t i = 0; i < scatterDirection.size(); ++i)
        scatterDirection[i].accumulate(other.scatterDirection[i], scale);
}

void PixelMaps::scale(double factor) {
    forEach(*this, [&](auto& map) { map.scale(factor); });
}

void PixelMaps::normalize() {
    forEach(*this, [](auto& map) { map.normalize(); });
}

TemporaryMaps::TemporaryMaps(const TaisSettings& s, int lightCount) {
    emplaceEnabled(*this, s, lightCount);
}

void TemporaryMaps::clear() {
    for (auto* m : {&time, &scatterDistance, &bifurcation, &lightSelection})
        if (*m) (*m)->clear();
    for (auto* m : {&lens, &pointOnLight})
        if (*m) (*m)->clear();
    for (TemporaryMap2D& m : scatterDirection)
        m.clear();
}

void TemporaryMaps::addFinishedTo(PixelMaps& m, double worldFloorShare) const {
    addFinished(time, m.time, true, worldFloorShare);
    addFinished(scatterDistance, m.scatterDistance, true, worldFloorShare);
    addFinished(bifurcation, m.bifurcation, false, worldFloorShare);
    addFinished(lightSelection, m.lightSelection, false, worldFloorShare);
    addFinished(lens, m.lens, true, worldFloorShare);
    addFinished(pointOnLight, m.pointOnLight, true, worldFloorShare);
    for (size_t i = 0; i < scatterDirection.size(); ++i)
        scatterDirection[i].addFinishedTo(m.scatterDirection[i],
                                          worldFloorShare / scatterDirection[i].cells());
}

}  // namespace rr::tais
