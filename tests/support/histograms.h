// Histograms over the domains of the warps and sampling routines, with the expected count of
// each cell obtained by integrating the claimed density numerically: a 16 × 16-point
// Gauss–Legendre product rule (accurate for smooth, peaked densities), and the midpoint rule on
// a 96² sub-grid on cells at the edge of the support (cells where the density is zero at some
// nodes only, and empty cells beside non-empty ones). The outline of a
// light or a warp's domain crosses cells; a cell holding a sliver of the support must not be
// given an expected count of zero, and its mass must be accurate.
#pragma once

#include <functional>
#include <vector>

#include "math/vector.h"

namespace rr::test {

// Directions binned by (z, φ) — equal-area cells, since dω = dz dφ — over z ∈ [zMin, 1].
// The band must contain the density's support: samples below zMin go to an extra cell that
// expects none. Place support boundaries inside cells, not on cell edges, so that rounding
// cannot push a sample into a cell that expects nothing.
class DirectionHistogram {
  public:
    DirectionHistogram(int zCells, int phiCells, double zMin = -1.0);
    // Counts `w` with `weight` (1 for a sample; a quadrature point's mass when the histogram
    // accumulates expected counts).
    void add(const Vec3& w, double weight = 1.0);
    // Index in counts() of the cell holding `w` (the last, extra cell when below zMin).
    size_t cellOf(const Vec3& w) const;
    const std::vector<double>& counts() const { return counts_; }
    // Expected counts for `samples` draws from the density `pdf` (per steradian).
    std::vector<double> expected(const std::function<double(const Vec3&)>& pdf,
                                 double samples) const;
    // The unit direction at fractional cell coordinates (z index + fraction, φ index + fraction).
    Vec3 direction(double zCell, double phiCell) const;

  private:
    int zCells_, phiCells_;
    double zMin_;
    std::vector<double> counts_;  // zCells·phiCells + 1 (outside)
};

// Points of the rectangle [x0, x1] × [y0, y1] binned on a regular grid; samples outside go to
// an extra cell.
class PlaneHistogram {
  public:
    PlaneHistogram(int xCells, int yCells, double x0, double x1, double y0, double y1);
    void add(const Vec2& p);
    const std::vector<double>& counts() const { return counts_; }
    std::vector<double> expected(const std::function<double(const Vec2&)>& pdf,
                                 double samples) const;

  private:
    int xCells_, yCells_;
    double x0_, x1_, y0_, y1_;
    std::vector<double> counts_;
};

}  // namespace rr::test
