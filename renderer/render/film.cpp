#include "render/film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace rr {

Rgb SplatSums::estimate() const {
    const double w = weight();
    if (!(w > 0)) return Rgb(0.0f);
    return Rgb(float(weighted(0) / w), float(weighted(1) / w), float(weighted(2) / w));
}

Rgb SplatSums::varianceOfEstimate() const {
    // Σ w²(L − R)² / ((Σ w)² − Σ w²), R = Σ w·L / Σ w.
    const double w = weight(), w2 = squaredWeight();
    const double denominator = w * w - w2;
    if (!(w > 0) || !(denominator > 0)) return Rgb(0.0f);
    float v[3];
    for (int c = 0; c < 3; ++c) {
        const double r = weighted(c) / w;
        const double spread = squaredWeightedSquares(c) - 2 * r * squaredWeighted(c) + r * r * w2;
        v[c] = static_cast<float>(std::max(0.0, spread) / denominator);
    }
    return Rgb(v[0], v[1], v[2]);
}

void SplatTile::reset(int x0, int y0, int x1, int y1) {
    x0_ = x0;
    y0_ = y0;
    x1_ = std::max(x0, x1);
    y1_ = std::max(y0, y1);
    sums_.assign(size_t(x1_ - x0_) * size_t(y1_ - y0_), SplatSums{});
}

void SplatTile::add(const ReconstructionFilter& filter, int x, int y, Vec2 offset, const Rgb& value,
                    double scale) {
    ReconstructionFilter::Taps wx, wy;
    filter.taps(offset.x, &wx);
    filter.taps(offset.y, &wy);
    const SplatTerms terms(value);
    const int reach = filter.reach();
    // The centres within the radius, inside the tile (which holds the image's part of it).
    const int ty0 = std::max(y - reach + wy.first, y0_),
              ty1 = std::min(y - reach + wy.last + 1, y1_);
    const int tx0 = std::max(x - reach + wx.first, x0_),
              tx1 = std::min(x - reach + wx.last + 1, x1_);
    for (int ty = ty0; ty < ty1; ++ty) {
        const double rowWeight = wy.weight[size_t(ty - y + reach)] * scale;
        SplatSums* row = &sums_[size_t(ty - y0_) * size_t(x1_ - x0_)];
        for (int tx = tx0; tx < tx1; ++tx)
            row[tx - x0_].add(wx.weight[size_t(tx - x + reach)] * rowWeight, terms);
    }
}

Film::Film(int width, int height, const ReconstructionFilter& filter)
    : width_(width), height_(height), filter_(filter), counts_(size_t(width) * height) {
    if (splats())
        sums_.resize(counts_.size());
    else
        pixels_.resize(counts_.size());
}

void Film::add(int x, int y, const Rgb& value) {
    const size_t i = index(x, y);
    Pixel& p = pixels_[i];
    for (int c = 0; c < 3; ++c) {
        const double v = value[c];
        p.sum[c] += v;
        p.sumSquares[c] += v * v;
    }
    ++counts_[i];
}

void Film::beginRound(size_t units) {
    roundUnits_ = units;
    if (tiles_.size() < units) tiles_.resize(units);
    for (size_t u = 0; u < units; ++u)
        tiles_[u].reset(0, 0, 0, 0);
}

SplatTile& Film::openTile(size_t unit, int x0, int y0, int x1, int y1) {
    if (unit >= roundUnits_) throw std::logic_error("a film tile for a unit outside the round");
    SplatTile& tile = tiles_[unit];
    if (x1 <= x0 || y1 <= y0) {
        tile.reset(0, 0, 0, 0);
        return tile;
    }
    const int reach = filter_.reach();
    tile.reset(std::max(0, x0 - reach), std::max(0, y0 - reach), std::min(width_, x1 + reach),
               std::min(height_, y1 + reach));
    return tile;
}

void Film::endRound() {
    if (!splats() || roundUnits_ == 0) return;
    constexpr int kRowsPerTask = 8;
    tbb::parallel_for(tbb::blocked_range<int>(0, height_, kRowsPerTask),
                      [&](const tbb::blocked_range<int>& rows) {
                          for (size_t u = 0; u < roundUnits_; ++u) {
                              const SplatTile& tile = tiles_[u];
                              if (tile.empty()) continue;
                              const int y0 = std::max(rows.begin(), tile.y0());
                              const int y1 = std::min(rows.end(), tile.y1());
                              for (int y = y0; y < y1; ++y)
                                  for (int x = tile.x0(); x < tile.x1(); ++x)
                                      sums_[index(x, y)].add(tile.at(x, y));
                          }
                      });
    roundUnits_ = 0;
}

Rgb Film::mean(int x, int y) const {
    const size_t i = index(x, y);
    if (splats()) return sums_[i].estimate();
    const Pixel& p = pixels_[i];
    if (counts_[i] == 0) return Rgb(0.0f);
    const double n = counts_[i];
    return Rgb(float(p.sum[0] / n), float(p.sum[1] / n), float(p.sum[2] / n));
}

Rgb Film::varianceOfMean(int x, int y) const {
    const size_t i = index(x, y);
    if (splats()) return sums_[i].varianceOfEstimate();
    const Pixel& p = pixels_[i];
    if (counts_[i] < 2) return Rgb(0.0f);
    const double n = counts_[i];
    float v[3];
    for (int c = 0; c < 3; ++c) {
        const double m = p.sum[c] / n;
        const double sampleVariance = (p.sumSquares[c] - n * m * m) / (n - 1);
        v[c] = static_cast<float>(sampleVariance > 0 ? sampleVariance / n : 0.0);
    }
    return Rgb(v[0], v[1], v[2]);
}

}  // namespace rr
