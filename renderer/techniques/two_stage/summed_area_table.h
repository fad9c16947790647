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
        const double s = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
        return s > 0 ? s : 0.0;
    }

  private:
    double at(int x, int y) const { return table_[size_t(y) * (width_ + 1) + x]; }

    int width_ = 0, height_ = 0;
    std::vector<double> table_;  // (width + 1) × (height + 1): sums of the texels above-left
};

}  // namespace rr::two_stage
