// What a TAIS render uses (Cline, Adams & Egbert 2008): which of Table 1's importance maps,
// their sizes, the world-space mixing fraction α of eq. (2), and how the image is split into
// bands for parallel rendering.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "integrators/path_settings.h"

namespace rr::tais {

// Table 1's maps. Preimage-space maps warp a decision's uniform coordinates (p_tot = p_map ·
// p_is, eq. 3); world-space maps are a second sampling strategy mixed in with probability α
// (p_tot = α p_map + (1 − α) p_is, eq. 2).
enum class MapKind : uint8_t {
    Time,              // 1-D preimage: instant in the shutter interval (motion blur)
    Lens,              // 2-D preimage: point on the aperture (depth of field)
    ScatterDistance,   // 1-D preimage: free-flight distance of the camera ray in a medium
    Bifurcation,       // discrete world: reflect or transmit, per path vertex index
    LightSelection,    // discrete world: which light next-event estimation samples, per vertex
    PointOnLight,      // 2-D preimage: the light sample's coordinates
    ScatterDirection,  // 2-D world: direction of the first (and second) non-specular bounce
    Count
};
inline constexpr int kMapKinds = static_cast<int>(MapKind::Count);

std::string_view mapName(MapKind kind);
bool parseMapName(std::string_view name, MapKind* out);

// Whether each map is preimage-space (true) or world-space (Table 1, "Space").
constexpr bool isPreimageMap(MapKind kind) {
    return kind == MapKind::Time || kind == MapKind::Lens || kind == MapKind::ScatterDistance ||
           kind == MapKind::PointOnLight;
}

// Which part of a sample's value L(x) a map is credited with (§3.3 adds |L(x)| to every map).
enum class Credit : uint8_t {
    Path,        // |L(x)|, as the paper says
    Downstream,  // |the part of L(x) gathered after the decision|: what the decision can change
};

struct TaisSettings {
    PathSettings path;
    // Maps asked for; with `automatic`, the maps whose decision the scene has (resolved against
    // the scene before rendering).
    std::array<bool, kMapKinds> enabled{};
    bool automatic = true;
    // Map sizes, chosen over all figures from the sensitivity table
    // (results/tables/tais_map_sizes.md, quick profile at e9438a2): 64 cells for both 1-D maps
    // (the best scatter-distance size; tied with the best, 32, for time, where 128 lost
    // significantly), 32² for the lens (16² and 64² lost by far) and the point on the light
    // (tied with 16²), 16² for scatter directions (the best of 8², 16², 32², 64² on fig. 4,
    // ×1.02 [1.01, 1.03] against the paper's PT, measured after the choice; on fig. 7 32² lost
    // to 16² within its interval).
    int timeCells = 64;
    int scatterDistanceCells = 64;
    int lensSize = 32;  // 2-D maps: size × size cells
    int pointOnLightSize = 32;
    int scatterDirectionSize = 16;
    int scatterDirectionBounces = 1;  // fig. 14: a second map for the second bounce
    int bifurcationVertices = 8;      // path vertices with a reflect/transmit entry each
    // Path vertices whose next-event estimation has its own light-selection entries (beyond
    // the paper, whose one map steers the first vertex, as 1 does).
    int lightSelectionVertices = 1;
    float alpha = 0.5f;               // eq. (2); the paper's renderings use 0.5
    // Beyond the paper: a world map mixes in only the part of its mass that samples credited
    // (importance_map.h), with α scaled by that part's share of the decision's mass (a share of
    // mass, not a count of samples); the even rest (the uniform start, the floor, the maps of
    // pixels that gave this one no credit) is left to standard sampling, so a decision no
    // credited sample has reached is standard sampling's. False: the whole map with the
    // paper's α.
    bool alphaFollowsEvidence = true;
    // The share of a world-space map's mass spread evenly over its entries before
    // renormalising (§3.3: "a tiny value ... to avoid underflow"); world maps need no more,
    // since standard sampling explores with probability 1 − α. With alphaFollowsEvidence the
    // floor is never drawn from: it only lowers α by about this share.
    double worldFloorShare = 1e-3;
    Credit credit = Credit::Downstream;
    bool contributionFilter = false;  // eq. (4), biased: reported separately
    int bandRows = 32;                // rows scanned by one task (see tais_integrator.h)
    int bandWarmupRows = 4;           // rows of the band above scanned first, samples discarded

    bool uses(MapKind kind) const { return enabled[static_cast<int>(kind)]; }
};

}  // namespace rr::tais
