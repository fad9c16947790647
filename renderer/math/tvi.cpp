#include "math/tvi.h"

#include <cmath>

namespace rr {

// Both functions are Ferwerda et al. 1996, eqs. for the cone/rod TVI: piecewise fits of
// log10 threshold against log10 La. The published pieces nearly, but not exactly, meet at the
// breakpoints; they are used as published. La ≤ 0 (black, or negative pixel values) has no
// logarithm and takes the lower plateau, which is the limit as La → 0.

namespace {

// log10 tvi = floor for log10 La <= low; log10 La + highOffset for log10 La >= high;
// (scale·log10 La + offset)^exponent + floor in between.
struct TviFit {
    double low, high, floor, highOffset, scale, offset, exponent;
};

double fittedTvi(double la, const TviFit& f) {
    if (!(la > 0)) return std::pow(10.0, f.floor);
    const double x = std::log10(la);
    const double logTvi = x <= f.low    ? f.floor
                          : x >= f.high ? x + f.highOffset
                                        : std::pow(f.scale * x + f.offset, f.exponent) + f.floor;
    return std::pow(10.0, logTvi);
}

}  // namespace

double photopicTvi(double la) {
    return fittedTvi(la, {-2.6, 1.9, -0.72, -1.255, 0.249, 0.65, 2.7});
}

double scotopicTvi(double la) {
    return fittedTvi(la, {-3.94, -1.44, -2.86, -0.395, 0.405, 1.6, 2.2});
}

}  // namespace rr
