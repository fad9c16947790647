// Piecewise-constant density on the unit square over a width × height grid of cells (row 0 at
// y = 0), sampled by inverting a marginal distribution over rows and a conditional one over the
// cells of the chosen row (Pharr et al., "Physically Based Rendering", §13.6.7: the standard
// two-step inversion). Used for environment maps, where a cell is a texel.
#pragma once

#include <span>
#include <vector>

#include "math/vector.h"
#include "sampling/distribution1d.h"

namespace rr {

class Distribution2D {
  public:
    Distribution2D() = default;
    // `weights`: width·height finite, non-negative values, row-major; all zero → uniform.
    Distribution2D(std::span<const float> weights, int width, int height);

    // A point of [0,1)² with density *pdf (per unit area of the square): the cell is chosen
    // with probability weight/sum (its row-major index in *cell, when asked), the point
    // uniformly inside it.
    Vec2 sample(Vec2 u, float* pdf, int* cell = nullptr) const;
    // Density at a point of [0,1]² (points on the upper edges belong to the last cells).
    float pdf(Vec2 p) const;
    // The inverse of sample(): the u that sample() maps to the point `p` of a cell of non-zero
    // weight (TAIS's point-on-light map indexes light samples by these coordinates).
    Vec2 invert(Vec2 p) const;

  private:
    int width_ = 0, height_ = 0;
    Distribution1D rows_;                  // marginal over rows (row sums)
    std::vector<Distribution1D> columns_;  // per row: conditional over its cells
};

}  // namespace rr
