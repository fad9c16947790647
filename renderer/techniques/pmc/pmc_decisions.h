// The decisions population Monte Carlo's PMC-HI estimator makes at a shading point, registered
// with the technique (TechniqueRegistry::addDecisions). Their ids are part of every coordinate's
// hash: they keep the values they had when the images were made.
#pragma once

#include <array>

#include "sampling/decisions.h"

namespace rr::pmc {

// 1-D: the residual offset of an iteration's deterministic mixture counts
inline constexpr Decision kMixtureCount{15, 1, "mixture_count"};
// 1-D: lobe of a sample drawn from the BSDF component
inline constexpr Decision kMixtureLobe{16, 1, "mixture_lobe"};
// 2-D: a sample's point on a light or direction, for any component
inline constexpr Decision kMixtureDirection{17, 2, "mixture_direction"};

inline constexpr std::array kDecisions{kMixtureCount, kMixtureLobe, kMixtureDirection};

}  // namespace rr::pmc
