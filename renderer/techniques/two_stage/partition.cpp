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

// Heap order: the larger split potential first, the lower index on ties (deterministic).
bool heapBefore(const std::pair<double, int>& a, const std::pair<double, int>& b) {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
}

double meanCornerF(const Region& r) {
    return (r.f00 + r.f10 + r.f01 + r.f11) / 4;
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
    root.sum = table.sum(root.x0, root.y0, root.x1, root.y1);
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
    const Region& leaf = regions_[size_t(leafAt(x, std::min(double(y), root.y1 - 0.5)))];
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
        // Eq. (4), where both axes can be split.
        const double dx = (r.f10 - r.f00) * (r.f10 - r.f00) + (r.f11 - r.f01) * (r.f11 - r.f01);
        const double dy = (r.f01 - r.f00) * (r.f01 - r.f00) + (r.f11 - r.f10) * (r.f11 - r.f10);
        bool alongX = dx * (r.x1 - r.x0) > dy * (r.y1 - r.y0);
        if (r.x1 - r.x0 < 2) alongX = false;
        if (r.y1 - r.y0 < 2) alongX = true;
        const int at = alongX ? (r.x0 + r.x1) / 2 : (r.y0 + r.y1) / 2;
        if (split(i, alongX, at) < 0) break;
        ++done;
    }
    computeWeights();
    stats_.regions = static_cast<uint32_t>(regions_.size());
}

int Partition::leafAt(double x, double y) const {
    int i = 0;
    while (!regions_[size_t(i)].isLeaf()) {
        const Region& r = regions_[size_t(i)];
        i = r.childA + (((r.splitX ? x : y) < r.splitAt) ? 0 : 1);
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
    for (const double py : {y - 0.5, y + 0.5}) {
        if (py < rootY0 || py > rootY1) continue;
        const int leaf = leafAt(x, py);
        if (regions_[size_t(leaf)].x0 < x && x < regions_[size_t(leaf)].x1) split(leaf, true, x);
    }
    const double py = std::clamp(double(y), double(rootY0), rootY1 - 0.5);
    for (const double px : {x > 0 ? x - 0.5 : width - 0.5, x + 0.5}) {  // x wraps around
        const int side = leafAt(px, py);
        if (regions_[size_t(side)].y0 < y && y < regions_[size_t(side)].y1) split(side, false, y);
    }
}

int Partition::split(int i, bool alongX, int at) {
    if (regions_.size() + 2 > kMaxRegions) return -1;
    const Region r = regions_[size_t(i)];  // a copy: the vector may grow
    Region a = r, b = r;
    if (alongX) {
        const double top = evaluate(at, r.y0), bottom = evaluate(at, r.y1);
        a.x1 = b.x0 = at;
        a.f10 = b.f00 = top;
        a.f11 = b.f01 = bottom;
    } else {
        const double left = evaluate(r.x0, at), right = evaluate(r.x1, at);
        a.y1 = b.y0 = at;
        a.f01 = b.f00 = left;
        a.f11 = b.f10 = right;
    }
    a.sum = table_->sum(a.x0, a.y0, a.x1, a.y1);
    b.sum = table_->sum(b.x0, b.y0, b.x1, b.y1);
    const int first = static_cast<int>(regions_.size());
    Region& parent = regions_[size_t(i)];
    parent.childA = first;
    parent.splitX = alongX;
    parent.splitAt = at;
    regions_.push_back(a);
    regions_.push_back(b);
    pushCandidate(first);
    pushCandidate(first + 1);
    // Fig. 5's cascade, breadth-first through the neighbours each cascaded split meets; the
    // outermost call drains it.
    pending_.push_back(i);
    if (pending_.size() == 1)
        while (!pending_.empty()) {
            const int next = pending_.front();
            cascade(next);
            pending_.erase(pending_.begin());
        }
    return first;
}

// Region `i` has just been split: split each neighbour whose edge the split line meets, along
// the same line, where f at the meeting point exceeds the sum of f at the neighbour's two
// corners on that edge.
void Partition::cascade(int i) {
    const Region r = regions_[size_t(i)];
    // Copies: splitting a neighbour may grow the vector.
    const Region a = regions_[size_t(r.childA)];
    const int rootY0 = regions_[0].y0, rootY1 = regions_[0].y1;
    const int width = table_->width();
    // `before`: the neighbour is on the lower side (above an x-split, left of a y-split).
    auto tryNeighbour = [&](double px, double py, bool before, double meeting) {
        const int n = leafAt(px, py);
        const Region& nr = regions_[size_t(n)];
        const int at = r.splitAt;
        const bool crosses = r.splitX ? (nr.x0 < at && at < nr.x1) : (nr.y0 < at && at < nr.y1);
        if (!crosses) return;
        // The neighbour's two corners on the shared edge.
        const double corners = r.splitX ? (before ? nr.f01 + nr.f11 : nr.f00 + nr.f10)
                                        : (before ? nr.f10 + nr.f11 : nr.f00 + nr.f01);
        if (!(meeting > corners)) return;
        if (split(n, r.splitX, at) >= 0) ++stats_.cascades;
    };
    if (r.splitX) {
        const int x = r.splitAt;
        if (r.y0 > rootY0) tryNeighbour(x, r.y0 - 0.5, true, a.f10);
        if (r.y1 < rootY1) tryNeighbour(x, r.y1 + 0.5, false, a.f11);
    } else {
        const int y = r.splitAt;
        // x wraps around: the map's left and right edges are one meridian.
        tryNeighbour(r.x0 > 0 ? r.x0 - 0.5 : width - 0.5, y, true, a.f01);
        tryNeighbour(r.x1 < width ? r.x1 + 0.5 : 0.5, y, false, a.f11);
    }
}

void Partition::pushCandidate(int i) {
    const Region& r = regions_[size_t(i)];
    if (r.x1 - r.x0 < 2 && r.y1 - r.y0 < 2) return;  // a single texel
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
