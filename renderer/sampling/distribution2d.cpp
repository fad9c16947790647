#include "sampling/distribution2d.h"

#include <algorithm>

namespace rr {

Distribution2D::Distribution2D(std::span<const float> weights, int width, int height)
    : width_(width), height_(height) {
    std::vector<float> rowSums(size_t(height), 0.0f);
    columns_.reserve(size_t(height));
    for (int r = 0; r < height; ++r) {
        const std::span<const float> row = weights.subspan(size_t(r) * width, size_t(width));
        double sum = 0;
        for (float w : row)
            sum += w;
        rowSums[size_t(r)] = static_cast<float>(sum);
        columns_.emplace_back(row);
    }
    rows_ = Distribution1D(rowSums);
}

Vec2 Distribution2D::sample(Vec2 u, float* pdf, int* cell) const {
    float rowPmf, columnPmf, v, s;
    const int row = rows_.sample(u.y, &rowPmf, &v);
    const int col = columns_[size_t(row)].sample(u.x, &columnPmf, &s);
    // The remapped u lies in [0, 1): the point stays inside its cell, so pdf() of the
    // returned point finds the same cell (up to the rounding of the division below).
    *pdf = rowPmf * columnPmf * float(width_) * float(height_);
    if (cell) *cell = row * width_ + col;
    return {(float(col) + s) / float(width_), (float(row) + v) / float(height_)};
}

float Distribution2D::pdf(Vec2 p) const {
    const int col = std::clamp(static_cast<int>(p.x * float(width_)), 0, width_ - 1);
    const int row = std::clamp(static_cast<int>(p.y * float(height_)), 0, height_ - 1);
    return rows_.pmf(row) * columns_[size_t(row)].pmf(col) * float(width_) * float(height_);
}

Vec2 Distribution2D::invert(Vec2 p) const {
    const float x = std::clamp(p.x, 0.0f, 1.0f) * float(width_);
    const float y = std::clamp(p.y, 0.0f, 1.0f) * float(height_);
    const int col = std::clamp(static_cast<int>(x), 0, width_ - 1);
    const int row = std::clamp(static_cast<int>(y), 0, height_ - 1);
    return {columns_[size_t(row)].invert(col, std::clamp(x - float(col), 0.0f, 1.0f)),
            rows_.invert(row, std::clamp(y - float(row), 0.0f, 1.0f))};
}

}  // namespace rr
