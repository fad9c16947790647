#include "techniques/two_stage/partition.h"

#include <algorithm>
#include <cmath>

namespace rr::two_stage {

namespace {

// The floor's share of the mean corner f (see partition.h).
constexpr double kFloorFraction = 1e-3;
// A bound on the tree, against runaway cascades: splits stop there (the tree stays valid).
constexpr size_t kMaxRegions = size_t(1) << 16;
// f values beyond this are taken as this, so that sums of weights stay finite.
constexpr double kMaxF = 1e100;

// Heap order: the larger split potential first, the lower index on ties (deterministic). A
// function object rather than a function, so that the heap operations inline it.
constexpr auto heapBefore = [](const std::pair<double, int>& a, const std::pair<double, int>& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
};

double meanCornerF(const Region& r) {
    return (r.f00 + r.f10 + r.f01 + r.f11) / 4;
}

// A split of a region: along x (at a column) or along y (at a row), and the line's end points.
struct SplitLine {
    bool alongX;
    int at;

    int x0(const Region& r) const { return alongX ? at : r.x0; }
    int y0(const Region& r) const { return alongX ? r.y0 : at; }
    int x1(const Region& r) const { return alongX ? at : r.x1; }
    int y1(const Region& r) const { return alongX ? r.y1 : at; }
};

// The refinement split of a leaf: eq. (4)'s axis, where both axes can be split, at the integer
// midpoint.
SplitLine refinementLine(const Region& r) {
    const double dx = (r.f10 - r.f00) * (r.f10 - r.f00) + (r.f11 - r.f01) * (r.f11 - r.f01);
    const double dy = (r.f01 - r.f00) * (r.f01 - r.f00) + (r.f11 - r.f10) * (r.f11 - r.f10);
    bool alongX = dx * (r.x1 - r.x0) > dy * (r.y1 - r.y0);
    if (r.x1 - r.x0 < 2) alongX = false;
    if (r.y1 - r.y0 < 2) alongX = true;
    return {alongX, alongX ? (r.x0 + r.x1) / 2 : (r.y0 + r.y1) / 2};
}

}  // namespace

double Partition::evaluate(int x, int y) {
    ++stats_.evaluations;
    const double v = f_->at(x, y);
    if (!(v > 0)) return 0;  // also NaN
    return std::min(v, kMaxF);
}

void Partition::build(const SummedAreaTable& table, const PartitionRequest& request,
                      const ProductFactor& f) {
    table_ = &table;
    f_ = &f;
    refinementSplits_ = request.splits;
    floor_ = 0;
    regions_.clear();
    heap_.clear();
    pending_.clear();
    stats_ = {};
    Region root;
    root.x1 = table.width();
    root.y0 = request.rootY0;
    root.y1 = request.rootY1;
    root.f00 = evaluate(root.x0, root.y0);
    root.f10 = evaluate(root.x1, root.y0);
    root.f01 = evaluate(root.x0, root.y1);
    root.f11 = evaluate(root.x1, root.y1);
    root.sat00 = table.at(root.x0, root.y0);
    root.sat10 = table.at(root.x1, root.y0);
    root.sat01 = table.at(root.x0, root.y1);
    root.sat11 = table.at(root.x1, root.y1);
    root.sum = SummedAreaTable::sum(root.sat00, root.sat10, root.sat01, root.sat11);
    regions_.push_back(root);
    pushCandidate(0);
    // Fig. 3: the normal and the column half a turn away.
    splitAtPoint(request.normalX, request.normalY);
    splitAtPoint(request.normalX + table.width() / 2, request.normalY);
    for (int i = 0; i < request.peakCount; ++i)
        splitAtPoint(request.peaks[size_t(i)].first, request.peaks[size_t(i)].second);
}

bool Partition::offerPeak(int x, int y) {
    const int width = table_->width();
    x = ((x % width) + width) % width;
    const Region& root = regions_[0];
    if (y < root.y0 || y > root.y1) return false;
    const Region& leaf = regions_[size_t(leafAt(x, std::min(y, root.y1 - 1)))];
    if (!(evaluate(x, y) > meanCornerF(leaf))) return false;
    splitAtPoint(x, y);
    return true;
}

void Partition::finish() {
    for (uint32_t done = 0; done < refinementSplits_ && !heap_.empty();) {
        std::pop_heap(heap_.begin(), heap_.end(), heapBefore);
        const int i = heap_.back().second;
        heap_.pop_back();
        const Region& r = regions_[size_t(i)];
        if (!r.isLeaf()) continue;  // split by a cascade since it was queued
        const SplitLine line = refinementLine(r);
        if (split(i, line.alongX, line.at) < 0) break;
        ++done;
    }
    computeWeights();
    stats_.regions = static_cast<uint32_t>(regions_.size());
}

// Texel (x, y) is in the first child when it lies before the split line. In integers (rather
// than at the texel's centre in doubles) each step of the descent is a compare and an add: the
// cascades and splits at points look up two leaves per split.
int Partition::leafAt(int x, int y) const {
    int i = 0;
    while (!regions_[size_t(i)].isLeaf()) {
        const Region& r = regions_[size_t(i)];
        i = r.childA + int((r.splitX ? x : y) >= r.splitAt);
    }
    return i;
}

int Partition::depth() const {
    std::vector<int> depths(regions_.size(), 0);
    int deepest = 0;
    for (size_t i = 0; i < regions_.size(); ++i) {
        const Region& r = regions_[i];
        if (r.isLeaf()) {
            deepest = std::max(deepest, depths[i]);
            continue;
        }
        depths[size_t(r.childA)] = depths[size_t(r.childA) + 1] = depths[i] + 1;
    }
    return deepest;
}

// "Split at (x, y)" (§2.2): the leaf holding the point along x, then the leaves on both sides
// of the new line along y. A point on an existing edge splits the leaves on both sides of that
// edge (Fig. 3: the second initial point lies on the first one's row, and both rows are split
// there, giving six regions). A coordinate already on an edge is not split again.
void Partition::splitAtPoint(int x, int y) {
    const int width = table_->width();
    x = ((x % width) + width) % width;
    const int rootY0 = regions_[0].y0, rootY1 = regions_[0].y1;
    for (const int row : {y - 1, y}) {  // the texels above and below the point
        if (row < rootY0 || row >= rootY1) continue;
        const int leaf = leafAt(x, row);
        if (regions_[size_t(leaf)].x0 < x && x < regions_[size_t(leaf)].x1) split(leaf, true, x);
    }
    const int row = std::clamp(y, rootY0, rootY1 - 1);
    for (const int column : {x > 0 ? x - 1 : width - 1, x}) {  // x wraps around
        const int side = leafAt(column, row);
        if (regions_[size_t(side)].y0 < y && y < regions_[size_t(side)].y1) split(side, false, y);
    }
}

int Partition::split(int i, bool alongX, int at) {
    if (regions_.size() + 2 > kMaxRegions) return -1;
    const SplitLine line{alongX, at};
    const Region& r = regions_[size_t(i)];
    const int x0 = line.x0(r), y0 = line.y0(r), x1 = line.x1(r), y1 = line.y1(r);
    // Both end points' table entries are requested before either f is evaluated (a
    // refinement split's were, when its region was queued).
    table_->prefetch(x0, y0);
    table_->prefetch(x1, y1);
    const double f0 = evaluate(x0, y0), f1 = evaluate(x1, y1);
    const double sat0 = table_->at(x0, y0), sat1 = table_->at(x1, y1);
    const int first = static_cast<int>(regions_.size());
    // The children start as copies of the parent (push_back copies before it reallocates).
    regions_.push_back(regions_[size_t(i)]);
    regions_.push_back(regions_[size_t(i)]);
    Region& parent = regions_[size_t(i)];
    Region& a = regions_[size_t(first)];
    Region& b = regions_[size_t(first) + 1];
    if (alongX) {
        a.x1 = b.x0 = at;
        a.f10 = b.f00 = f0;
        a.f11 = b.f01 = f1;
        a.sat10 = b.sat00 = sat0;
        a.sat11 = b.sat01 = sat1;
    } else {
        a.y1 = b.y0 = at;
        a.f01 = b.f00 = f0;
        a.f11 = b.f10 = f1;
        a.sat01 = b.sat00 = sat0;
        a.sat11 = b.sat10 = sat1;
    }
    a.sum = SummedAreaTable::sum(a.sat00, a.sat10, a.sat01, a.sat11);
    b.sum = SummedAreaTable::sum(b.sat00, b.sat10, b.sat01, b.sat11);
    parent.childA = first;
    parent.splitX = alongX;
    parent.splitAt = at;
    pushCandidate(first);
    pushCandidate(first + 1);
    // Fig. 5's cascade, breadth-first through the neighbours each cascaded split meets; the
    // outermost call drains it.
    pending_.push_back(i);
    if (pending_.size() == 1) {
        for (size_t k = 0; k < pending_.size(); ++k)
            cascade(pending_[k]);
        pending_.clear();
    }
    return first;
}

// Region `i` has just been split: split each neighbour whose edge the split line meets, along
// the same line, where f at the meeting point exceeds the sum of f at the neighbour's two
// corners on that edge.
void Partition::cascade(int i) {
    const Region& r = regions_[size_t(i)];
    const Region& a = regions_[size_t(r.childA)];
    // Copied out: splitting a neighbour may grow the vector.
    const bool alongX = r.splitX;
    const int at = r.splitAt, x0 = r.x0, y0 = r.y0, x1 = r.x1, y1 = r.y1;
    // f at the split line's end points (the first child's corners there).
    const double f0 = alongX ? a.f10 : a.f01, f1 = a.f11;
    const int rootY0 = regions_[0].y0, rootY1 = regions_[0].y1;
    const int width = table_->width();
    // The neighbour is the leaf holding texel (column, row), beyond r's edge; `before`: it is
    // on the lower side (above an x-split, left of a y-split). Its corners' f are never
    // negative, so where f at the meeting point is 0 no neighbour is split and none is looked
    // for.
    auto tryNeighbour = [&](int column, int row, bool before, double meeting) {
        if (!(meeting > 0)) return;
        const int n = leafAt(column, row);
        const Region& nr = regions_[size_t(n)];
        const bool crosses = alongX ? (nr.x0 < at && at < nr.x1) : (nr.y0 < at && at < nr.y1);
        if (!crosses) return;
        // The neighbour's two corners on the shared edge.
        const double corners = alongX ? (before ? nr.f01 + nr.f11 : nr.f00 + nr.f10)
                                      : (before ? nr.f10 + nr.f11 : nr.f00 + nr.f01);
        if (!(meeting > corners)) return;
        if (split(n, alongX, at) >= 0) ++stats_.cascades;
    };
    if (alongX) {
        if (y0 > rootY0) tryNeighbour(at, y0 - 1, true, f0);
        if (y1 < rootY1) tryNeighbour(at, y1, false, f1);
    } else {
        // x wraps around: the map's left and right edges are one meridian.
        tryNeighbour(x0 > 0 ? x0 - 1 : width - 1, at, true, f0);
        tryNeighbour(x1 < width ? x1 : 0, at, false, f1);
    }
}

void Partition::pushCandidate(int i) {
    const Region& r = regions_[size_t(i)];
    if (r.x1 - r.x0 < 2 && r.y1 - r.y0 < 2) return;  // a single texel
    // The summed-area table's entries at the ends of either split the leaf may get (eq. (4)
    // picks the axis if it is popped; asking for both is cheaper than deciding here): far
    // apart in the 4 MB table, they mostly miss the cache, and requested now they have arrived
    // by the time a refinement split needs them.
    const int midX = (r.x0 + r.x1) / 2, midY = (r.y0 + r.y1) / 2;
    table_->prefetch(midX, r.y0);
    table_->prefetch(midX, r.y1);
    table_->prefetch(r.x0, midY);
    table_->prefetch(r.x1, midY);
    heap_.emplace_back(splitPotential(r), i);
    std::push_heap(heap_.begin(), heap_.end(), heapBefore);
}

// Eq. (3): σ_f · sum · area, σ_f = ½ √Σ(f − f̄)² over the four corners.
double Partition::splitPotential(const Region& r) const {
    const double mean = meanCornerF(r);
    const double d00 = r.f00 - mean, d10 = r.f10 - mean, d01 = r.f01 - mean, d11 = r.f11 - mean;
    const double sigma = 0.5 * std::sqrt(d00 * d00 + d10 * d10 + d01 * d01 + d11 * d11);
    return sigma * r.sum * double(r.area());
}

void Partition::computeWeights() {
    double weighted = 0, mass = 0;
    for (const Region& r : regions_)
        if (r.isLeaf()) {
            weighted += r.sum * meanCornerF(r);
            mass += r.sum;
        }
    const double meanF = mass > 0 ? weighted / mass : 0;
    // With f zero at every corner the tree falls back to the map alone.
    floor_ = meanF > 0 ? kFloorFraction * meanF : 1.0;
    // Children come after their parent: backwards, every child is done before its parent.
    for (size_t k = regions_.size(); k-- > 0;) {
        Region& r = regions_[k];
        if (r.isLeaf()) {
            r.weight = r.sum * (meanCornerF(r) + floor_);  // eq. (5)
            continue;
        }
        const Region& a = regions_[size_t(r.childA)];
        const Region& b = regions_[size_t(r.childA) + 1];
        r.weight = a.weight + b.weight;
        r.probA = r.weight > 0 ? a.weight / r.weight : 0.5;     // eq. (6)
        r.areaFractionA = double(a.area()) / double(r.area());  // eq. (7)
    }
}

}  // namespace rr::two_stage
