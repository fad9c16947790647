// A pixel's importance maps (TAIS §3.3): the maps a render uses, each present only when it is
// enabled, and the temporary maps that collect a pixel's samples.
//
// Layouts:
//  - bifurcation: 2 entries per path vertex index v < bifurcationVertices, reflect_v at 2v and
//    transmit_v at 2v + 1 (fig. 12, "reflect0, transmit1, transmit2");
//  - light selection: one entry per light, by the light's index in the scene, for each path
//    vertex v < lightSelectionVertices: light l of vertex v at v · lights + l;
//  - scatter direction: a world-space direction w ↦ (φ / 2π, (1 − w.z) / 2) ∈ [0, 1)². The paper
//    indexes the map by (θ, φ); we use cos θ instead of θ so that every cell covers the same
//    solid angle (4π / cells) and the map's density is finite at the poles.
#pragma once

#include <optional>
#include <vector>

#include "math/vector.h"
#include "techniques/tais/importance_map.h"
#include "techniques/tais/tais_settings.h"
#include "techniques/tais/temporary_map.h"

namespace rr::tais {

// The scatter-direction map's coordinates of a unit direction, and back.
Vec2 directionToMap(const Vec3& w);
Vec3 mapToDirection(Vec2 p);
// Solid-angle density of a direction whose map coordinates have density `mapPdf` on [0, 1)².
inline float directionPdfFromMap(float mapPdf) {
    return mapPdf * (0.25f / 3.14159265358979323846f);
}

inline int bifurcationCell(int vertex, bool reflect) {
    return 2 * vertex + (reflect ? 0 : 1);
}
inline int lightSelectionCell(int vertex, int light, int lights) {
    return vertex * lights + light;
}

struct PixelMaps {
    std::optional<InvertedMap1D> time, scatterDistance, bifurcation, lightSelection;
    std::optional<InvertedMap2D> lens, pointOnLight;
    std::vector<InvertedMap2D> scatterDirection;  // [bounce]
    int lights = 0;                               // the scene's: the light-selection layout

    // Uniform maps of the enabled kinds (a pixel with no rendered neighbour).
    static PixelMaps uniform(const TaisSettings& settings, int lightCount);

    // Each map the sum of the parts' (same layout; 1 to 8 parts), divided by its own total if
    // `normalize` (InvertedMap1D::assignSum).
    void assignSum(std::span<const PixelMaps* const> parts, bool normalize);
    // Each map += entering's − leaving's (either may be null): a running window's step.
    void slide(const PixelMaps* entering, const PixelMaps* leaving);
    // Each map divided by its own total.
    void normalize();
};

struct TemporaryMaps {
    std::optional<TemporaryMap1D> time, scatterDistance, bifurcation, lightSelection;
    std::optional<TemporaryMap2D> lens, pointOnLight;
    std::vector<TemporaryMap2D> scatterDirection;

    TemporaryMaps(const TaisSettings& settings, int lightCount);
    void clear();
    // Algorithm 1, lines 22–24: each map normalised, the constant added (1/n for preimage
    // maps, a `worldFloorShare` of the mass for world maps), renormalised, inverted and added
    // to `maps`.
    void addFinishedTo(PixelMaps& maps, double worldFloorShare) const;
};

}  // namespace rr::tais
