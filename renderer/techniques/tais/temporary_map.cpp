#include "techniques/tais/temporary_map.h"

#include <algorithm>
#include <numeric>

namespace rr::tais {

namespace {

// map += the finished map of `weights`: (w / Σw + floor) / (1 + n · floor) per entry (lines
// 22–23), uniform when nothing was added.
template <class Map>
void addFinished(const std::vector<double>& weights, Map& map, double floor) {
    const double sum = std::accumulate(weights.begin(), weights.end(), 0.0);
    const double n = double(weights.size());
    if (!(sum > 0)) {
        map.accumulateUniform(1.0 / n);
        return;
    }
    const double norm = 1.0 / (1.0 + floor * n);
    map.accumulateWeights(weights, norm / sum, floor * norm);
}

}  // namespace

void TemporaryMap1D::splat(float u, double value) {
    const int c = cellOf(u, cells());
    for (int i = std::max(c - 1, 0); i <= std::min(c + 1, cells() - 1); ++i)
        weights_[i] += value;
}

InvertedMap1D TemporaryMap1D::finish(double floorPerEntry) const {
    InvertedMap1D map(cells());
    map.scale(0);
    addFinishedTo(map, floorPerEntry);
    return map;
}

void TemporaryMap1D::addFinishedTo(InvertedMap1D& map, double floorPerEntry) const {
    addFinished(weights_, map, floorPerEntry);
}

void TemporaryMap2D::splat(Vec2 u, double value) {
    const int cx = cellOf(u.x, width_), cy = cellOf(u.y, height_);
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, height_ - 1); ++y)
        for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, width_ - 1); ++x)
            weights_[size_t(y) * width_ + x] += value;
}

InvertedMap2D TemporaryMap2D::finish(double floorPerEntry) const {
    InvertedMap2D map(width_, height_);
    map.scale(0);
    addFinishedTo(map, floorPerEntry);
    return map;
}

void TemporaryMap2D::addFinishedTo(InvertedMap2D& map, double floorPerEntry) const {
    addFinished(weights_, map, floorPerEntry);
}

}  // namespace rr::tais
