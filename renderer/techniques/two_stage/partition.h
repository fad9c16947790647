// Stage 1 of two-stage sampling (Cline et al. 2006 §2.2): per shading point, an axis-aligned
// BSP tree over the lat-long map whose leaves approximate the product of the environment map
// (exact, through the summed-area table) and f = fr·|cos θ| (bilinear between f at the leaf's
// corners). Built by
//  - the root: the rows of the normal's hemisphere, all columns (Fig. 3);
//  - the initial partition: splits at the normal's grid point and at the column half a turn
//    away, 6 regions with monotonic cos θ;
//  - splits at the BSDF's peaks;
//  - exactly `splits` more splits, each of the leaf with the largest split potential σ_f·sum·area
//    (eq. 3), along the axis of eq. (4), at its midpoint;
//  - after every split, cascades into the neighbours the split line meets (Fig. 5), where f at
//    the meeting point exceeds the sum of the neighbour's two corners on that edge (x wraps);
//  - region weights sum·(mean corner f + floor) (eq. 5), summed up the tree, with each inner
//    node's probability and area fraction of its first child (eqs. 6, 7).
// The floor (not in the paper) keeps every texel of the root with non-zero radiance at a
// non-zero density: a leaf whose four corners miss a narrow lobe or a bulge of the horizon would
// otherwise get no samples where the integrand is not zero, and the estimate would be biased. It
// is 10⁻³ of the mean corner f (weighted by the map), so it takes 0.1 % of the samples.
//
// The tree lives in a vector the partition reuses: after the first shading points of a thread it
// allocates nothing.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "techniques/two_stage/summed_area_table.h"

namespace rr::two_stage {

// f = luminance(fr·|cos θ|) at a grid point (x, y) of the map, x ∈ [0, W], y ∈ [0, H] (x = W is
// the direction of x = 0).
class ProductFactor {
  public:
    virtual ~ProductFactor() = default;
    virtual double at(int x, int y) const = 0;
};

struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;         // texels [x0, x1) × [y0, y1)
    double f00 = 0, f10 = 0, f01 = 0, f11 = 0;  // f at (x0, y0), (x1, y0), (x0, y1), (x1, y1)
    // The summed-area table's entries at the same corners: a split reads only the two at its
    // new grid points.
    double sat00 = 0, sat10 = 0, sat01 = 0, sat11 = 0;
    double sum = 0;   // the summed-area table over the region
    int childA = -1;  // the children are childA (lower coordinates) and childA + 1; -1: a leaf
    bool splitX = false;
    int splitAt = 0;
    double weight = 0;         // eq. (5), or the children's sum
    double probA = 0;          // eq. (6)
    double areaFractionA = 0;  // eq. (7)

    bool isLeaf() const { return childA < 0; }
    int64_t area() const { return int64_t(x1 - x0) * (y1 - y0); }
};

// Where the partition starts: grid points (rounded map positions) and the budget of splits.
struct PartitionRequest {
    int rootY0 = 0, rootY1 = 0;  // the root's rows
    int normalX = 0, normalY = 0;
    std::array<std::pair<int, int>, 16> peaks;  // as many as LobePeaks holds
    int peakCount = 0;
    uint32_t splits = 0;  // refinement splits (eq. 3), besides the cascades

    void addPeak(int x, int y) {
        if (peakCount < int(peaks.size())) peaks[size_t(peakCount++)] = {x, y};
    }
};

// Counts for the performance report.
struct PartitionStats {
    uint32_t regions = 0, cascades = 0, evaluations = 0;
};

class Partition {
  public:
    // Builds the tree for `request` over `table`'s map; `peaks` are split at in order. The
    // caller may add peaks afterwards (splitAtPeak) and must then call finish().
    void build(const SummedAreaTable& table, const PartitionRequest& request,
               const ProductFactor& f);
    // The paper's BSDF-sample peaks (§2.2): a direction becomes a peak, split at, when f there
    // exceeds the mean f at the corners of the leaf it falls in. Before finish().
    bool offerPeak(int x, int y);
    // The refinement splits and the weights: the tree is then ready for warping.
    void finish();

    const Region& root() const { return regions_[0]; }
    const Region& region(int i) const { return regions_[size_t(i)]; }
    // The leaf holding texel (x, y), x ∈ [0, W).
    int leafAt(int x, int y) const;
    // The floor added to every corner f in the weights (and below the leaves, in the warp).
    double floor() const { return floor_; }
    const PartitionStats& stats() const { return stats_; }
    // The deepest leaf's depth (the root is 0).
    int depth() const;

  private:
    double evaluate(int x, int y);
    int split(int region, bool alongX, int at);
    void splitAtPoint(int x, int y);
    void cascade(int region);
    void pushCandidate(int region);
    double splitPotential(const Region& r) const;
    void computeWeights();

    const SummedAreaTable* table_ = nullptr;
    const ProductFactor* f_ = nullptr;
    uint32_t refinementSplits_ = 0;
    double floor_ = 0;
    std::vector<Region> regions_;
    std::vector<std::pair<double, int>> heap_;  // leaves by split potential
    std::vector<int> pending_;                  // regions just split, neighbours unchecked
    PartitionStats stats_;
};

}  // namespace rr::two_stage
