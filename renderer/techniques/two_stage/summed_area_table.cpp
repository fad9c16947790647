#include "techniques/two_stage/summed_area_table.h"

#include <cmath>
#include <numbers>

#include "scene/lights/environment_map.h"

namespace rr::two_stage {

SummedAreaTable::SummedAreaTable(const EnvironmentMap& map)
    : width_(map.width()), height_(map.height()), table_(size_t(width_ + 1) * (height_ + 1), 0.0) {
    for (int y = 0; y < height_; ++y) {
        // cos(latitude) = sin(θ) with θ = π t from the +Y pole, at the row's centre.
        const double cosLatitude = std::sin(std::numbers::pi * (y + 0.5) / height_);
        double row = 0;
        for (int x = 0; x < width_; ++x) {
            row += double(map.texel(x, y).luminance()) * cosLatitude;
            table_[size_t(y + 1) * (width_ + 1) + x + 1] = at(x + 1, y) + row;
        }
    }
}

}  // namespace rr::two_stage
