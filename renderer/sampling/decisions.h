// Every random decision a path makes has a name. A sample coordinate is addressed by
// (decision, path vertex, repeat), so a technique can find — and replace — the coordinates
// that feed one decision (TAIS's importance maps warp exactly these: time, lens, light
// selection, point on light, scatter direction, bifurcation, scatter distance).
#pragma once

#include <cstdint>

namespace rr {

enum class Decision : uint8_t {
    FilmPosition,     // 2-D: position inside the pixel (never warped: a splatting film reads it)
    Time,             // 1-D: instant within the shutter interval
    Lens,             // 2-D: point on the thin-lens aperture
    LightSelect,      // 1-D: which light to sample for next-event estimation
    LightPoint,       // 2-D: point (or direction) on the chosen light
    BsdfLobe,         // 1-D: which lobe (e.g. Fresnel reflect vs transmit: TAIS bifurcation)
    BsdfDirection,    // 2-D: direction within the chosen lobe
    MediumDistance,   // 1-D: free-flight distance in a participating medium
    RussianRoulette,  // 1-D: path termination
    // Resampled importance sampling (techniques/ris):
    ResampleCount,       // 1-D: random rounding of a fractional candidate or sample count
    ResampleSelect,      // 1-D: whether the reservoir keeps a candidate
    CandidateLobe,       // 1-D: lobe of a candidate drawn from the BSDF
    CandidateDirection,  // 2-D: direction of a candidate drawn from a directional source
    // Two-stage sampling (techniques/two_stage):
    PeakLobe,       // 1-D: lobe of a BSDF sample drawn to find a peak
    PeakDirection,  // 2-D: direction of that sample
    // Population Monte Carlo (techniques/pmc):
    MixtureCount,      // 1-D: the residual offset of an iteration's deterministic mixture counts
    MixtureLobe,       // 1-D: lobe of a sample drawn from the BSDF component
    MixtureDirection,  // 2-D: a sample's point on a light or direction, for any component
    Count
};

constexpr int dimensionCount(Decision d) {
    switch (d) {
        case Decision::FilmPosition:
        case Decision::Lens:
        case Decision::LightPoint:
        case Decision::BsdfDirection:
        case Decision::CandidateDirection:
        case Decision::PeakDirection:
        case Decision::MixtureDirection:
            return 2;
        default:
            return 1;
    }
}

constexpr const char* decisionName(Decision d) {
    switch (d) {
        case Decision::FilmPosition:
            return "film_position";
        case Decision::Time:
            return "time";
        case Decision::Lens:
            return "lens";
        case Decision::LightSelect:
            return "light_select";
        case Decision::LightPoint:
            return "light_point";
        case Decision::BsdfLobe:
            return "bsdf_lobe";
        case Decision::BsdfDirection:
            return "bsdf_direction";
        case Decision::MediumDistance:
            return "medium_distance";
        case Decision::RussianRoulette:
            return "russian_roulette";
        case Decision::ResampleCount:
            return "resample_count";
        case Decision::ResampleSelect:
            return "resample_select";
        case Decision::CandidateLobe:
            return "candidate_lobe";
        case Decision::CandidateDirection:
            return "candidate_direction";
        case Decision::PeakLobe:
            return "peak_lobe";
        case Decision::PeakDirection:
            return "peak_direction";
        case Decision::MixtureCount:
            return "mixture_count";
        case Decision::MixtureLobe:
            return "mixture_lobe";
        case Decision::MixtureDirection:
            return "mixture_direction";
        case Decision::Count:
            break;
    }
    return "?";
}

// Where in a path a decision is made. Camera decisions use vertex 0. `repeat` numbers
// repeated draws of one decision at one vertex (several light samples per pixel sample);
// `repeatCount` tells structured samplers how many draws to stratify together.
struct DecisionSite {
    Decision decision;
    uint32_t vertex = 0;
    uint32_t repeat = 0;
    uint32_t repeatCount = 1;

    constexpr uint64_t key() const {
        return (static_cast<uint64_t>(vertex) << 40) | (static_cast<uint64_t>(decision) << 32) |
               repeat;
    }
};

}  // namespace rr
