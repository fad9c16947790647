// The decisions two-stage sampling makes at a shading point besides the standard LightPoint
// (the direction warped through the partition), registered with the technique
// (TechniqueRegistry::addDecisions). Their ids are part of every coordinate's hash: they keep
// the values they had when the images were made.
#pragma once

#include <array>

#include "sampling/decisions.h"

namespace rr::two_stage {

// 1-D: lobe of a BSDF sample drawn to find a peak (peaks "bsdf", §2.2)
inline constexpr Decision kPeakLobe{13, 1, "peak_lobe"};
// 2-D: direction of that sample
inline constexpr Decision kPeakDirection{14, 2, "peak_direction"};

inline constexpr std::array kDecisions{kPeakLobe, kPeakDirection};

}  // namespace rr::two_stage
