#include "techniques/tais/importance_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rr::tais {

namespace {

// The point at `fraction` of `cell`, in float, nudged so that it lies in that cell as pdf()
// and cdf() locate it: rounding (cell + fraction)/cells can land on the next cell's edge,
// where the density differs.
float positionInCell(int cell, double fraction, int cells) {
    float x = std::min(static_cast<float>((cell + fraction) / cells), kOneMinusEpsilon);
    while (cellOf(x, cells) > cell)
        x = std::nextafter(x, 0.0f);
    while (cellOf(x, cells) < cell)
        x = std::nextafter(x, 1.0f);
    return x;
}

}  // namespace

InvertedMap1D::InvertedMap1D(int cells) : sums_(static_cast<size_t>(cells) + 1, 0.0) {
    if (cells < 1) throw std::invalid_argument("an importance map needs at least one cell");
    uniform_ = cells;  // weight 1 in every cell
}

InvertedMap1D InvertedMap1D::fromWeights(std::span<const double> weights) {
    InvertedMap1D map(static_cast<int>(weights.size()));
    map.uniform_ = 0;
    for (size_t i = 0; i < weights.size(); ++i) {
        if (!(weights[i] >= 0) || !std::isfinite(weights[i]))
            throw std::invalid_argument("importance map weights must be finite and >= 0");
        map.sums_[i + 1] = map.sums_[i] + weights[i];
    }
    if (!(map.total() > 0)) throw std::invalid_argument("importance map weights are all zero");
    return map;
}

void InvertedMap1D::accumulate(const InvertedMap1D& other, double scale) {
    if (other.sums_.size() != sums_.size())
        throw std::invalid_argument("importance maps of different sizes");
    for (size_t i = 0; i < sums_.size(); ++i)
        sums_[i] += scale * other.sums_[i];
    uniform_ += scale * other.uniform_;
}

namespace {

// Σ parts[k][i] in the order of assigning parts[0] and accumulating the others.
double sumAt(std::span<const std::vector<double>* const> parts, size_t i) {
    double s = (*parts[0])[i];
    for (size_t k = 1; k < parts.size(); ++k)
        s += (*parts[k])[i];
    return s;
}

// to = Σ parts · factor, element by element (factor 1: exact, as no scaling). The usual part
// counts (one to three: a pixel's neighbours) are one pass over plain arrays, which the
// compiler vectorises; more (the window summed afresh) add part after part.
void assignScaledSum(std::vector<double>& to, std::span<const std::vector<double>* const> parts,
                     double factor) {
    for (const auto* p : parts)  // the loops below assume no aliasing (__restrict)
        if (p == &to) throw std::logic_error("an importance map summed into itself");
    double* __restrict out = to.data();
    const size_t n = to.size();
    const double* __restrict a = parts[0]->data();
    if (parts.size() == 1) {
        for (size_t i = 0; i < n; ++i)
            out[i] = a[i] * factor;
        return;
    }
    const double* __restrict b = parts[1]->data();
    if (parts.size() == 2) {
        for (size_t i = 0; i < n; ++i)
            out[i] = (a[i] + b[i]) * factor;
        return;
    }
    const double* __restrict c = parts[2]->data();
    if (parts.size() == 3) {
        for (size_t i = 0; i < n; ++i)
            out[i] = ((a[i] + b[i]) + c[i]) * factor;
        return;
    }
    for (size_t i = 0; i < n; ++i)
        out[i] = sumAt(parts, i) * factor;
}

void slideSums(std::vector<double>& sums, const std::vector<double>* entering,
               const std::vector<double>* leaving) {
    if (entering == &sums || leaving == &sums)  // the loops below assume no aliasing
        throw std::logic_error("an importance map slid by itself");
    double* __restrict s = sums.data();
    const size_t n = sums.size();
    const double* __restrict in = entering ? entering->data() : nullptr;
    const double* __restrict out = leaving ? leaving->data() : nullptr;
    if (in && out) {
        for (size_t i = 0; i < n; ++i)
            s[i] = (s[i] + in[i]) - out[i];
    } else if (in) {
        for (size_t i = 0; i < n; ++i)
            s[i] += in[i];
    } else if (out) {
        for (size_t i = 0; i < n; ++i)
            s[i] -= out[i];
    }
}

}  // namespace

void InvertedMap1D::assignSum(std::span<const InvertedMap1D* const> parts, bool normalize) {
    if (parts.empty() || parts.size() > kMaxSummedMaps)
        throw std::invalid_argument("a sum of 1 to 8 importance maps");
    const std::vector<double>* sums[kMaxSummedMaps];
    double uniform = parts[0]->uniform_;
    for (size_t k = 0; k < parts.size(); ++k) {
        if (parts[k]->sums_.size() != sums_.size())
            throw std::invalid_argument("importance maps of different sizes");
        sums[k] = &parts[k]->sums_;
        if (k > 0) uniform += parts[k]->uniform_;
    }
    const std::span<const std::vector<double>* const> all(sums, parts.size());
    const double factor = normalize ? 1.0 / (sumAt(all, sums_.size() - 1) + uniform) : 1.0;
    assignScaledSum(sums_, all, factor);
    uniform_ = uniform * factor;
}

void InvertedMap1D::slide(const InvertedMap1D* entering, const InvertedMap1D* leaving) {
    slideSums(sums_, entering ? &entering->sums_ : nullptr, leaving ? &leaving->sums_ : nullptr);
    if (entering) uniform_ += entering->uniform_;
    if (leaving) uniform_ -= leaving->uniform_;
}

void InvertedMap1D::accumulateWeights(std::span<const double> weights, double scale,
                                      double perCell) {
    if (weights.size() + 1 != sums_.size())
        throw std::invalid_argument("importance maps of different sizes");
    double running = 0;
    for (size_t i = 0; i < weights.size(); ++i) {
        running += scale * weights[i];
        sums_[i + 1] += running;
    }
    accumulateUniform(perCell);
}

void InvertedMap1D::scale(double factor) {
    for (double& s : sums_)
        s *= factor;
    uniform_ *= factor;
}

Inversion invertRunningSums(std::span<const double> sums, float u, double perCell) {
    const int cells = int(sums.size()) - 1;
    // Offsets from the slice's start, so that a slice far along a long map keeps its
    // resolution: g(i) = f(i) − f(0), non-decreasing from 0 to the slice's mass.
    auto g = [&](int i) { return (sums[size_t(i)] - sums[0]) + i * perCell; };
    const double target = double(u) * g(cells);  // < g(cells) for u < 1
    // The first g above the target ends the cell: g(cell) ≤ target < g(cell + 1), so the cell
    // has positive weight and zero-weight cells are never drawn.
    //
    // The search branches on purpose. A learned map concentrates (the lens map of fig. 6 on
    // the ~1 % of the lens that sees a light), so most draws end in the same few cells, the
    // comparisons mostly go one way and predict well. A branch-free search making the same
    // comparisons (issue 40) was slower on fig. 6: 24.5–25.7 % of the render against
    // 22.7–23.5 % (three alternating perf runs), although callgrind's simple branch predictor
    // counted 97 % fewer misses in it.
    int lo = 0, hi = cells + 1;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (g(mid) > target)
            hi = mid;
        else
            lo = mid + 1;
    }
    const int cell = std::clamp(lo - 1, 0, cells - 1);
    const double w = g(cell + 1) - g(cell);
    return {cell, w > 0 ? std::clamp((target - g(cell)) / w, 0.0, 1.0) : 0.0};
}

float InvertedMap1D::warp(float u, float* pdf) const {
    const Inversion inv = invert(u);
    *pdf = float(cells() * weight(inv.cell) / total());
    return positionInCell(inv.cell, inv.fraction, cells());
}

float InvertedMap1D::pdf(float uPrime) const {
    return float(cells() * weight(cellOf(uPrime, cells())) / total());
}

float InvertedMap1D::cdf(float uPrime) const {
    // The CDF is continuous, so locating u' on either side of a cell edge gives one value.
    const int cell = cellOf(uPrime, cells());
    const double within = std::clamp(double(uPrime), 0.0, 1.0) * cells() - cell;
    const double below = sums_[cell] + cell * uniformPerCell(MapPart::Whole);
    return float((below + within * weight(cell)) / total());
}

InvertedMap2D::InvertedMap2D(int width, int height)
    : width_(width), height_(height), sums_(size_t(width + 1) * height, 0.0), rowTotals_(height) {
    // Uniform: weight 1 in every cell, so every row's total is `width`.
    rowTotals_.scale(width);
}

InvertedMap2D InvertedMap2D::fromWeights(std::span<const double> weights, int width, int height) {
    if (weights.size() != size_t(width) * height)
        throw std::invalid_argument("importance map weights do not match its size");
    for (double w : weights)
        if (!(w >= 0) || !std::isfinite(w))
            throw std::invalid_argument("importance map weights must be finite and >= 0");
    InvertedMap2D map(width, height);
    map.scale(0);
    map.accumulateWeights(weights, 1);
    if (!(map.total() > 0)) throw std::invalid_argument("importance map weights are all zero");
    return map;
}

void InvertedMap2D::accumulate(const InvertedMap2D& other, double scale) {
    if (other.width_ != width_ || other.height_ != height_)
        throw std::invalid_argument("importance maps of different sizes");
    for (size_t i = 0; i < sums_.size(); ++i)
        sums_[i] += scale * other.sums_[i];
    rowTotals_.accumulate(other.rowTotals_, scale);
}

void InvertedMap2D::assignSum(std::span<const InvertedMap2D* const> parts, bool normalize) {
    if (parts.empty() || parts.size() > kMaxSummedMaps)
        throw std::invalid_argument("a sum of 1 to 8 importance maps");
    const std::vector<double>* sums[kMaxSummedMaps];
    const InvertedMap1D* rows[kMaxSummedMaps];
    for (size_t k = 0; k < parts.size(); ++k) {
        if (parts[k]->width_ != width_ || parts[k]->height_ != height_)
            throw std::invalid_argument("importance maps of different sizes");
        sums[k] = &parts[k]->sums_;
        rows[k] = &parts[k]->rowTotals_;
    }
    rowTotals_.assignSum(std::span(rows, parts.size()), false);
    const double factor = normalize ? 1.0 / total() : 1.0;
    rowTotals_.scale(factor);
    assignScaledSum(sums_, std::span(sums, parts.size()), factor);
}

void InvertedMap2D::slide(const InvertedMap2D* entering, const InvertedMap2D* leaving) {
    slideSums(sums_, entering ? &entering->sums_ : nullptr, leaving ? &leaving->sums_ : nullptr);
    rowTotals_.slide(entering ? &entering->rowTotals_ : nullptr,
                     leaving ? &leaving->rowTotals_ : nullptr);
}

void InvertedMap2D::accumulateWeights(std::span<const double> weights, double scale,
                                      double perCell) {
    if (weights.size() != size_t(width_) * height_)
        throw std::invalid_argument("importance map weights do not match its size");
    // A row of zeros adds running sums of zero: never chosen on its own, and still linear.
    std::vector<double> totals(static_cast<size_t>(height_));
    for (int y = 0; y < height_; ++y) {
        double* row = sums_.data() + size_t(y) * (width_ + 1);
        double running = 0;
        for (int x = 0; x < width_; ++x) {
            running += scale * weights[size_t(y) * width_ + x];
            row[x + 1] += running;
        }
        totals[size_t(y)] = running;
    }
    rowTotals_.accumulateWeights(totals, 1, perCell * width_);
}

void InvertedMap2D::scale(double factor) {
    for (double& s : sums_)
        s *= factor;
    rowTotals_.scale(factor);
}

Vec2 InvertedMap2D::warp(Vec2 u, float* pdf, MapPart part) const {
    const Inversion r = rowTotals_.invert(u.y, part);
    const Inversion column = invertRunningSums(row(r.cell), u.x, uniformPerCell(part));
    *pdf = float(double(width_) * height_ * weight(column.cell, r.cell, part) / total(part));
    return {positionInCell(column.cell, column.fraction, width_),
            positionInCell(r.cell, r.fraction, height_)};
}

float InvertedMap2D::pdf(Vec2 uPrime, MapPart part) const {
    return float(double(width_) * height_ *
                 weight(cellOf(uPrime.x, width_), cellOf(uPrime.y, height_), part) / total(part));
}

Vec2 InvertedMap2D::cdf(Vec2 uPrime) const {
    const std::span<const double> sums = row(cellOf(uPrime.y, height_));
    const int cell = cellOf(uPrime.x, width_);
    const double within = std::clamp(double(uPrime.x), 0.0, 1.0) * width_ - cell;
    const double perCell = uniformPerCell(MapPart::Whole);
    const double below = sums[size_t(cell)] + cell * perCell;
    const double rowTotal = sums.back() + width_ * perCell;
    return {float((below + within * (sums[size_t(cell) + 1] - sums[size_t(cell)] + perCell)) /
                  rowTotal),
            rowTotals_.cdf(uPrime.y)};
}

}  // namespace rr::tais
