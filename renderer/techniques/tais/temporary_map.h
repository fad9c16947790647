// A pixel's temporary importance maps (TAIS §3.3, Algorithm 1 lines 2, 19 and 22–24): while
// the pixel renders, every sample adds |L(x)| at the coordinates of its decision — into that
// cell and the cells around it for continuous maps, "to promote exploration" (3 cells in 1-D,
// 3 × 3 in 2-D), into the one entry for discrete maps. When the pixel is done, the map is
// normalised, a constant is added to every entry (1/n for preimage-space maps, which keeps
// every pdf strictly positive and so the estimator unbiased; a tiny value for world-space
// maps), renormalised and inverted, ready to blend into the pixel's maps.
#pragma once

#include <algorithm>
#include <vector>

#include "techniques/tais/importance_map.h"

namespace rr::tais {

class TemporaryMap1D {
  public:
    explicit TemporaryMap1D(int cells) : weights_(static_cast<size_t>(cells), 0.0) {}

    void clear() { std::fill(weights_.begin(), weights_.end(), 0.0); }
    // Continuous maps: `value` into the cell of u ∈ [0, 1) and its two neighbours.
    void splat(float u, double value);
    // Discrete maps: `value` into one entry.
    void add(int cell, double value) { weights_[cell] += value; }

    // Lines 22–24: normalised, `floorPerEntry` added to every entry, renormalised, inverted.
    // A map that received nothing becomes uniform.
    InvertedMap1D finish(double floorPerEntry) const;
    // map += finish(floorPerEntry), without building the finished map.
    void addFinishedTo(InvertedMap1D& map, double floorPerEntry) const;
    int cells() const { return static_cast<int>(weights_.size()); }

  private:
    std::vector<double> weights_;
};

class TemporaryMap2D {
  public:
    TemporaryMap2D(int width, int height)
        : width_(width), height_(height), weights_(size_t(width) * height, 0.0) {}

    void clear() { std::fill(weights_.begin(), weights_.end(), 0.0); }
    // `value` into the cell of (u, v) ∈ [0, 1)² and its 3 × 3 neighbourhood (clipped at the
    // edges of the map).
    void splat(Vec2 u, double value);
    InvertedMap2D finish(double floorPerEntry) const;
    void addFinishedTo(InvertedMap2D& map, double floorPerEntry) const;
    int cells() const { return width_ * height_; }

  private:
    int width_, height_;
    std::vector<double> weights_;  // row-major
};

// The constant TAIS adds to preimage-space maps: 1/n for a map of n entries.
inline double preimageFloor(int entries) {
    return 1.0 / entries;
}

}  // namespace rr::tais
