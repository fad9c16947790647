// The preprocess of two-stage sampling (Cline et al. 2006 §2.1): a summed-area table, in double
// precision, of luminance(L)·cos(latitude) over a latitude-longitude environment map, so that
// the sum over any rectangle of texels is four look-ups. The cosine (at each row's centre)
// compensates for the map's foreshortening towards the poles: a texel's solid angle is
// 2π² cos(latitude) ds dt.
#pragma once

#include <cstddef>
#include <vector>

namespace rr {
class EnvironmentMap;
}

namespace rr::two_stage {

class SummedAreaTable {
  public:
    SummedAreaTable() = default;
    explicit SummedAreaTable(const EnvironmentMap& map);

    int width() const { return width_; }
    int height() const { return height_; }
    // Σ luminance·cos(latitude) over texels [x0, x1) × [y0, y1) (grid coordinates); never
    // negative.
    double sum(int x0, int y0, int x1, int y1) const {
        return sum(at(x0, y0), at(x1, y0), at(x0, y1), at(x1, y1));
    }
    // The same sum from the table's entries at the rectangle's corners (x0, y0), (x1, y0),
    // (x0, y1), (x1, y1): a caller that keeps them reads only the entries it has not seen.
    static double sum(double a00, double a10, double a01, double a11) {
        const double s = a11 - a01 - a10 + a00;
        return s > 0 ? s : 0.0;
    }
    // The entry at grid point (x, y): the sum over texels [0, x) × [0, y).
    double at(int x, int y) const { return table_[index(x, y)]; }
    // Asks for at(x, y)'s cache line ahead of the read: entries of distant grid points are
    // far apart in the 4 MB table and mostly miss the cache.
    void prefetch(int x, int y) const { __builtin_prefetch(&table_[index(x, y)]); }

  private:
    size_t index(int x, int y) const { return size_t(y) * (width_ + 1) + size_t(x); }

    int width_ = 0, height_ = 0;
    std::vector<double> table_;  // (width + 1) × (height + 1): sums of the texels above-left
};

}  // namespace rr::two_stage
