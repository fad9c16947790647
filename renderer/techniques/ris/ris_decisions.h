// The decisions resampled importance sampling makes at a shading point (ShadingPoint::decide1D
// and decide2D), registered with the technique (TechniqueRegistry::addDecisions). Their ids are
// part of every coordinate's hash: they keep the values they had when the images were made.
#pragma once

#include <array>

#include "sampling/decisions.h"

namespace rr::ris {

// 1-D: random rounding of a fractional candidate or sample count
inline constexpr Decision kResampleCount{9, 1, "resample_count"};
// 1-D: whether the reservoir keeps a candidate
inline constexpr Decision kResampleSelect{10, 1, "resample_select"};
// 1-D: lobe of a candidate drawn from the BSDF
inline constexpr Decision kCandidateLobe{11, 1, "candidate_lobe"};
// 2-D: direction of a candidate drawn from a directional source
inline constexpr Decision kCandidateDirection{12, 2, "candidate_direction"};

inline constexpr std::array kDecisions{kResampleCount, kResampleSelect, kCandidateLobe,
                                       kCandidateDirection};

}  // namespace rr::ris
