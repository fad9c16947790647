// Bounds for the numbers of a scene file, open or closed at each end.
#pragma once

#include <string>

namespace rr {

struct Range {
    double lo = -1e300, hi = 1e300;
    bool loOpen = false, hiOpen = false;

    static Range any() { return {}; }
    static Range positive() { return {0, 1e300, true, false}; }
    static Range nonNegative() { return {0, 1e300, false, false}; }
    static Range unit() { return {0, 1, false, false}; }  // [0, 1]
    static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
    static Range open(double lo, double hi) { return {lo, hi, true, true}; }
    static Range atLeast(double lo) { return {lo, 1e300, false, false}; }

    bool hasLo() const { return lo > -1e299; }
    bool hasHi() const { return hi < 1e299; }
    bool contains(double v) const;
    std::string describe() const;
};

}  // namespace rr
