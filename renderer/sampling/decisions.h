// Every random decision a path makes has a name. A sample coordinate is addressed by
// (decision, path vertex, repeat), so a technique can find — and replace — the coordinates
// that feed one decision (importance maps over a decision's coordinates warp exactly these:
// time, lens, light selection, point on light, scatter direction, bifurcation, scatter
// distance).
//
// The standard path's decisions are here; a technique that makes decisions of its own declares
// them in its folder (techniques/<name>/<name>_decisions.h) and lists them in its registration
// (TechniqueRegistry::addDecisions), which refuses an id or a name that is taken.
#pragma once

#include <array>
#include <cstdint>

namespace rr {

struct Decision {
    // Part of every coordinate's hash (DecisionSite::key): changing a decision's id changes
    // every image that draws it.
    uint8_t id;
    uint8_t dimensions;  // 1 or 2: drawn by PixelSample::get1D or get2D
    const char* name;    // snake_case, for messages

    // The standard path's decisions (defined below):
    // 2-D: position inside the pixel (never warped: a splatting film reads it)
    static const Decision FilmPosition;
    static const Decision Time;         // 1-D: instant within the shutter interval
    static const Decision Lens;         // 2-D: point on the thin-lens aperture
    static const Decision LightSelect;  // 1-D: which light to sample for next-event estimation
    static const Decision LightPoint;   // 2-D: point (or direction) on the chosen light
    // 1-D: which lobe (e.g. Fresnel reflect vs transmit: the path bifurcates)
    static const Decision BsdfLobe;
    static const Decision BsdfDirection;    // 2-D: direction within the chosen lobe
    static const Decision MediumDistance;   // 1-D: free-flight distance in a participating medium
    static const Decision RussianRoulette;  // 1-D: path termination
};

inline constexpr Decision Decision::FilmPosition{0, 2, "film_position"};
inline constexpr Decision Decision::Time{1, 1, "time"};
inline constexpr Decision Decision::Lens{2, 2, "lens"};
inline constexpr Decision Decision::LightSelect{3, 1, "light_select"};
inline constexpr Decision Decision::LightPoint{4, 2, "light_point"};
inline constexpr Decision Decision::BsdfLobe{5, 1, "bsdf_lobe"};
inline constexpr Decision Decision::BsdfDirection{6, 2, "bsdf_direction"};
inline constexpr Decision Decision::MediumDistance{7, 1, "medium_distance"};
inline constexpr Decision Decision::RussianRoulette{8, 1, "russian_roulette"};

// The standard decisions, which every technique's decisions must differ from.
inline constexpr std::array<Decision, 9> kStandardDecisions{
    Decision::FilmPosition,  Decision::Time,           Decision::Lens,
    Decision::LightSelect,   Decision::LightPoint,     Decision::BsdfLobe,
    Decision::BsdfDirection, Decision::MediumDistance, Decision::RussianRoulette};

// Where in a path a decision is made. Camera decisions use vertex 0. `repeat` numbers
// repeated draws of one decision at one vertex (several light samples per pixel sample);
// `repeatCount` tells structured samplers how many draws to stratify together.
struct DecisionSite {
    Decision decision;
    uint32_t vertex = 0;
    uint32_t repeat = 0;
    uint32_t repeatCount = 1;

    constexpr uint64_t key() const {
        return (static_cast<uint64_t>(vertex) << 40) | (static_cast<uint64_t>(decision.id) << 32) |
               repeat;
    }
};

}  // namespace rr
