// TAIS importance maps (Cline, Adams & Egbert 2008, §3.3 and Algorithm 1): piecewise-constant
// densities over n cells of [0, 1) (1-D maps: time, scatter distance; discrete maps: light
// selection, bifurcation) or w × h cells of [0, 1)² (2-D maps: lens, point on light, scatter
// direction).
//
// The paper keeps pixel maps "inverted" (as CDFs) for quick lookup and adds inverted maps
// together (Algorithm 1, line 24). We store each map as running sums of its cell weights, not
// normalised: every operation the algorithm performs — averaging the maps of seven
// neighbours (fig. 3), blending in a pixel's finished temporary map — is linear in the
// density, so it acts on the running sums directly, and sampling divides by the total. A 2-D
// map keeps running sums per row plus a running sum of the row totals (the marginal over y),
// the paper's "CDF for each row of the map, as well as an extra CDF of the Y axis marginal";
// unnormalised rows keep that layout linear too.
//
// A map's mass has two parts, kept apart: the part samples put there (`credited`, the running
// sums) and a part spread evenly over every cell (`uniform`, one number): the uniform start,
// the constant of line 23, and the finished map of every pixel that gave this map no credit
// (its paths never made the decision, or carried no light past it). The map's density is their
// sum (`MapPart::Whole`, the paper's); world maps can also be sampled from their credited part
// alone (MapPart::Credited, TaisSettings::alphaFollowsEvidence).
//
// A preimage-space map warps uniform coordinates u to u' = F⁻¹(u) before standard importance
// sampling, with density p_map(u') (TAIS: p_tot = p_map · p_is).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "math/vector.h"

namespace rr::tais {

// The cell that u ∈ [0, 1) falls in when [0, 1) is cut into `cells` equal cells.
inline int cellOf(float u, int cells) {
    return std::clamp(static_cast<int>(u * cells), 0, cells - 1);
}

// The most maps assignSum() adds in one call (a pixel's neighbours need at most 5).
inline constexpr size_t kMaxSummedMaps = 8;

// Which of a map's mass a density or a draw uses (see above).
enum class MapPart : uint8_t { Whole, Credited };

// Inversion of the running sums f(i) = sums[i] + i · perCell (`sums` of size cells + 1,
// non-decreasing, perCell ≥ 0, f(cells) > f(0)): the cell that u ∈ [0, 1) falls in under the
// inverse CDF, and the position within it. The sums may be a slice of a longer map's.
struct Inversion {
    int cell;
    double fraction;
};
Inversion invertRunningSums(std::span<const double> sums, float u, double perCell = 0);

class InvertedMap1D {
  public:
    // A uniform map of `cells` cells.
    explicit InvertedMap1D(int cells);
    // The map of non-negative, finite `weights` (not all zero), all credited.
    static InvertedMap1D fromWeights(std::span<const double> weights);

    int cells() const { return static_cast<int>(sums_.size()) - 1; }
    double total(MapPart part = MapPart::Whole) const {
        return sums_.back() + (part == MapPart::Whole ? uniform_ : 0.0);
    }
    double weight(int cell, MapPart part = MapPart::Whole) const {
        return sums_[cell + 1] - sums_[cell] + uniformPerCell(part);
    }
    double uniformMass() const { return uniform_; }

    // this += scale · other (same size): averaging and blending maps (§3.3).
    void accumulate(const InvertedMap1D& other, double scale = 1);
    // this = the sum of `parts` (same size; at least one), divided by its total if `normalize`:
    // one pass over memory instead of a copy, an accumulate() per further part and a
    // normalize(), and the same bits (the same operations in the same order).
    void assignSum(std::span<const InvertedMap1D* const> parts, bool normalize);
    // this += *entering − *leaving (either may be null) in one pass: a running window's step.
    void slide(const InvertedMap1D* entering, const InvertedMap1D* leaving);
    // this += the map of scale · `weights` (credited) + `perCell` in every cell (uniform),
    // without building it.
    void accumulateWeights(std::span<const double> weights, double scale, double perCell = 0);
    // this += `perCell` in every cell.
    void accumulateUniform(double perCell) { uniform_ += perCell * cells(); }
    void scale(double factor);
    // Divides by the total, so that maps of any history blend with equal weight.
    void normalize() { scale(1.0 / total()); }

    // Preimage warp: u ∈ [0, 1) → u' ∈ [0, 1) by inverting the piecewise-linear CDF, with the
    // density of u' in *pdf (cells · weight / total).
    float warp(float u, float* pdf) const;
    // Density of the warp at u' ∈ [0, 1].
    float pdf(float uPrime) const;
    // The CDF at u' ∈ [0, 1]: the inverse of warp() (its tests check warp() against it).
    float cdf(float uPrime) const;

    // Discrete maps, of one decision or of several, each on its own slice of cells
    // [first, first + count) (bifurcation and light selection per path vertex): the slice's
    // mass, and a cell of the slice with probability weight / slice total (which must be
    // positive; a cell of weight 0 is never drawn).
    double sliceTotal(int first, int count, MapPart part = MapPart::Whole) const {
        return sums_[first + count] - sums_[first] + count * uniformPerCell(part);
    }
    int sampleCellIn(int first, int count, float u, MapPart part = MapPart::Whole) const {
        const std::span<const double> slice(sums_.data() + first, size_t(count) + 1);
        return first + invertRunningSums(slice, u, uniformPerCell(part)).cell;
    }

    Inversion invert(float u, MapPart part = MapPart::Whole) const {
        return invertRunningSums(sums_, u, uniformPerCell(part));
    }

  private:
    double uniformPerCell(MapPart part) const {
        return part == MapPart::Whole ? uniform_ / cells() : 0.0;
    }

    std::vector<double> sums_;  // credited: sums_[i] = weight of cells < i; size cells + 1
    double uniform_ = 0;        // spread evenly over the cells
};

class InvertedMap2D {
  public:
    // A uniform map of width × height cells (row y covers v ∈ [y/height, (y+1)/height)).
    InvertedMap2D(int width, int height);
    // The map of `weights` (width · height, row-major, non-negative, finite, not all zero),
    // all credited.
    static InvertedMap2D fromWeights(std::span<const double> weights, int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    double total(MapPart part = MapPart::Whole) const { return rowTotals_.total(part); }
    double weight(int x, int y, MapPart part = MapPart::Whole) const {
        const double* row = rowSums(y);
        return row[x + 1] - row[x] + uniformPerCell(part);
    }

    void accumulate(const InvertedMap2D& other, double scale = 1);
    // As InvertedMap1D's.
    void assignSum(std::span<const InvertedMap2D* const> parts, bool normalize);
    void slide(const InvertedMap2D* entering, const InvertedMap2D* leaving);
    // this += the map of scale · `weights` (row-major, credited) + `perCell` in every cell.
    void accumulateWeights(std::span<const double> weights, double scale, double perCell = 0);
    void accumulateUniform(double perCell) { rowTotals_.accumulateUniform(perCell * width_); }
    void scale(double factor);
    void normalize() { scale(1.0 / total()); }

    // Warp of (u, v) ∈ [0, 1)²: v' by the marginal over rows, then u' within the row, with the
    // density of (u', v') on [0, 1)² under the map's `part`, whose total must be positive.
    Vec2 warp(Vec2 u, float* pdf, MapPart part = MapPart::Whole) const;
    float pdf(Vec2 uPrime, MapPart part = MapPart::Whole) const;
    // The inverse of warp(): (conditional CDF within the row, marginal CDF over rows).
    Vec2 cdf(Vec2 uPrime) const;

  private:
    const double* rowSums(int y) const { return sums_.data() + size_t(y) * (width_ + 1); }
    std::span<const double> row(int y) const { return {rowSums(y), size_t(width_) + 1}; }
    double uniformPerCell(MapPart part) const {
        return part == MapPart::Whole ? rowTotals_.uniformMass() / (double(width_) * height_) : 0.0;
    }

    int width_, height_;
    // Row y's credited running sums (unnormalised) at [y · (width + 1), (y + 1) · (width + 1)):
    // one contiguous block, so averaging and blending maps is one pass over memory.
    std::vector<double> sums_;
    // Running sums of the rows' credited totals; its uniform part is the whole map's, spread
    // evenly over the rows as over the cells.
    InvertedMap1D rowTotals_;
};

// TAIS fig. 3: a pixel's maps start as the average of its already-rendered neighbours' maps
// (seven in the paper; fewer at the image's edges and in its first row).
template <class Map>
Map averageOf(std::span<const Map* const> neighbours) {
    Map sum = *neighbours.front();
    for (size_t i = 1; i < neighbours.size(); ++i)
        sum.accumulate(*neighbours[i]);
    sum.scale(1.0 / neighbours.size());
    return sum;
}

}  // namespace rr::tais
