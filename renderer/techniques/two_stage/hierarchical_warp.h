// Stage 2 of two-stage sampling (Cline et al. 2006 §3, Appendix A): a point (s, t) of the unit
// square warped down the partition's tree (each inner node sends the share probA of the
// coordinate along its axis to its first child), then below the leaf through virtual regions
// down to a single texel (the longer axis split at its integer midpoint, f interpolated linearly
// along the leaf's edges, each half weighted by its summed-area sum times its corner f), and
// uniformly inside the texel. The density is tracked on the way; the appendix's typos are
// fixed here (`R = R->childA`, `t < probA`, the second f10 parameter is f01) and its last line
// divides by the Jacobian where it prints a multiplication (TwoStageEstimator).
//
// Everything is in double precision (the paper's s, t and probabilities are floats): a path of
// forty halvings would otherwise leave s with a few bits.
#pragma once

#include "techniques/two_stage/partition.h"

namespace rr::two_stage {

struct WarpedPoint {
    double x = 0, y = 0;  // texel coordinates in the map: the texel is (⌊x⌋, ⌊y⌋)
    double density = 0;   // per unit area of the image taken as [0, 1]²
};

// False when the partition has no weight (the map is black over the root).
bool warp(const Partition& partition, const SummedAreaTable& table, double s, double t,
          WarpedPoint* out);

// The density warp() gives texel-space point (x, y): 0 outside the root. For tests and for
// density queries of directions drawn otherwise.
double densityAt(const Partition& partition, const SummedAreaTable& table, double x, double y);

}  // namespace rr::two_stage
