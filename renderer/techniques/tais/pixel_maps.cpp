#include "techniques/tais/pixel_maps.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rr::tais {

namespace {

// The member `map` of each of `parts`, for the maps' own assignSum.
template <class Map, class Member>
void assignSumOf(Map& to, std::span<const PixelMaps* const> parts, Member member, bool normalize) {
    const Map* maps[kMaxSummedMaps];
    for (size_t k = 0; k < parts.size(); ++k)
        maps[k] = &member(*parts[k]);
    to.assignSum(std::span<const Map* const>(maps, parts.size()), normalize);
}

template <class Map, class Member>
void slideOf(Map& to, const PixelMaps* entering, const PixelMaps* leaving, Member member) {
    to.slide(entering ? &member(*entering) : nullptr, leaving ? &member(*leaving) : nullptr);
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

// Every enabled map, with the accessor of the same map in another PixelMaps.
template <class F>
void forEachWithAccessor(PixelMaps& maps, F&& f) {
    using P = const PixelMaps&;
    if (maps.time)
        f(
            *maps.time, [](P p) -> auto& { return *p.time; });
    if (maps.scatterDistance)
        f(
            *maps.scatterDistance, [](P p) -> auto& { return *p.scatterDistance; });
    if (maps.bifurcation)
        f(
            *maps.bifurcation, [](P p) -> auto& { return *p.bifurcation; });
    if (maps.lightSelection)
        f(
            *maps.lightSelection, [](P p) -> auto& { return *p.lightSelection; });
    if (maps.lens)
        f(
            *maps.lens, [](P p) -> auto& { return *p.lens; });
    if (maps.pointOnLight)
        f(
            *maps.pointOnLight, [](P p) -> auto& { return *p.pointOnLight; });
    for (size_t i = 0; i < maps.scatterDirection.size(); ++i)
        f(
            maps.scatterDirection[i], [i](P p) -> auto& { return p.scatterDirection[i]; });
}

void PixelMaps::assignSum(std::span<const PixelMaps* const> parts, bool normalize) {
    if (parts.empty() || parts.size() > kMaxSummedMaps)
        throw std::invalid_argument("a sum of 1 to 8 maps");
    forEachWithAccessor(
        *this, [&](auto& map, auto member) { assignSumOf(map, parts, member, normalize); });
}

void PixelMaps::slide(const PixelMaps* entering, const PixelMaps* leaving) {
    forEachWithAccessor(*this,
                        [&](auto& map, auto member) { slideOf(map, entering, leaving, member); });
}

void PixelMaps::normalize() {
    forEachWithAccessor(*this, [](auto& map, auto) { map.normalize(); });
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
