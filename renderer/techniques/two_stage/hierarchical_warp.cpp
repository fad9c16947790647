#include "techniques/two_stage/hierarchical_warp.h"

#include <algorithm>
#include <cmath>

namespace rr::two_stage {

namespace {

constexpr double kBelowOne = 0x1.fffffffffffffp-1;

// One step of the warp along one axis (Fig. 7): the coordinate u moves into the chosen child's
// own [0, 1), and the density is scaled by the child's share of the samples over its share of
// the area. True for the first child.
bool descend(double probA, double areaFractionA, double* u, double* density) {
    if (*u < probA) {
        *u = std::min(*u / probA, kBelowOne);
        *density *= probA / areaFractionA;
        return true;
    }
    *u = std::min((*u - probA) / (1 - probA), kBelowOne);
    *density *= (1 - probA) / (1 - areaFractionA);
    return false;
}

// A region below the partition's leaves: its texels and f at its corners (interpolated).
struct VirtualRegion {
    int x0, y0, x1, y1;
    double f00, f10, f01, f11;

    bool isTexel() const { return x1 - x0 <= 1 && y1 - y0 <= 1; }
    bool splitsAlongX() const { return x1 - x0 > y1 - y0; }
};

// A virtual region's two halves along its longer axis (at the integer midpoint), with the
// first half's probability and area fraction.
struct VirtualSplit {
    VirtualRegion first, second;
    double probA, areaFractionA;
};

bool splitVirtual(const VirtualRegion& r, const SummedAreaTable& table, double floor,
                  VirtualSplit* out) {
    VirtualRegion a = r, b = r;
    double fraction;
    if (r.splitsAlongX()) {
        const int mid = (r.x0 + r.x1) / 2;
        fraction = double(mid - r.x0) / double(r.x1 - r.x0);
        const double top = r.f00 + fraction * (r.f10 - r.f00);
        const double bottom = r.f01 + fraction * (r.f11 - r.f01);
        a.x1 = b.x0 = mid;
        a.f10 = b.f00 = top;
        a.f11 = b.f01 = bottom;
    } else {
        const int mid = (r.y0 + r.y1) / 2;
        fraction = double(mid - r.y0) / double(r.y1 - r.y0);
        const double left = r.f00 + fraction * (r.f01 - r.f00);
        const double right = r.f10 + fraction * (r.f11 - r.f10);
        a.y1 = b.y0 = mid;
        a.f01 = b.f00 = left;
        a.f11 = b.f10 = right;
    }
    // The partition's floor joins every corner, as in its leaves' weights.
    const double sumA =
        table.sum(a.x0, a.y0, a.x1, a.y1) * (a.f00 + a.f10 + a.f01 + a.f11 + 4 * floor);
    const double sumB =
        table.sum(b.x0, b.y0, b.x1, b.y1) * (b.f00 + b.f10 + b.f01 + b.f11 + 4 * floor);
    if (!(sumA + sumB > 0)) return false;
    *out = {a, b, sumA / (sumA + sumB), fraction};
    return true;
}

VirtualRegion leafRegion(const Region& leaf) {
    return {leaf.x0, leaf.y0, leaf.x1, leaf.y1, leaf.f00, leaf.f10, leaf.f01, leaf.f11};
}

double rootDensity(const SummedAreaTable& table, const Region& root) {
    return double(table.width()) * double(table.height()) / double(root.area());
}

}  // namespace

bool warp(const Partition& partition, const SummedAreaTable& table, double s, double t,
          WarpedPoint* out) {
    const Region* r = &partition.root();
    if (!(r->weight > 0)) return false;
    double density = rootDensity(table, *r);
    while (!r->isLeaf()) {
        const bool first = descend(r->probA, r->areaFractionA, r->splitX ? &s : &t, &density);
        r = &partition.region(r->childA + (first ? 0 : 1));
    }
    VirtualRegion v = leafRegion(*r);
    while (!v.isTexel()) {
        VirtualSplit split;
        if (!splitVirtual(v, table, partition.floor(), &split)) return false;
        const bool alongX = v.splitsAlongX();
        const bool first = descend(split.probA, split.areaFractionA, alongX ? &s : &t, &density);
        v = first ? split.first : split.second;
    }
    *out = {v.x0 + s, v.y0 + t, density};
    return std::isfinite(density) && density > 0;
}

double densityAt(const Partition& partition, const SummedAreaTable& table, double x, double y) {
    const Region* r = &partition.root();
    if (!(r->weight > 0) || x < r->x0 || x >= r->x1 || y < r->y0 || y >= r->y1) return 0;
    double density = rootDensity(table, *r);
    // The same choices as warp() makes, taken from the point's position.
    auto follow = [&](bool alongX, int at, double probA, double areaFractionA) {
        const bool first = (alongX ? x : y) < at;
        density *= first ? probA / areaFractionA : (1 - probA) / (1 - areaFractionA);
        return first;
    };
    while (!r->isLeaf()) {
        const bool first = follow(r->splitX, r->splitAt, r->probA, r->areaFractionA);
        r = &partition.region(r->childA + (first ? 0 : 1));
    }
    VirtualRegion v = leafRegion(*r);
    while (!v.isTexel()) {
        VirtualSplit split;
        if (!splitVirtual(v, table, partition.floor(), &split)) return 0;
        const bool alongX = v.splitsAlongX();
        const int at = alongX ? split.first.x1 : split.first.y1;
        v = follow(alongX, at, split.probA, split.areaFractionA) ? split.first : split.second;
    }
    return density;
}

}  // namespace rr::two_stage
