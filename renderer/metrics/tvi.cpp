#include "metrics/tvi.h"

#include <cmath>

namespace rr {

// Both functions are Ferwerda et al. 1996, eqs. for the cone/rod TVI: piecewise fits of
// log10 threshold against log10 La. The published pieces nearly, but not exactly, meet at the
// breakpoints; they are used as published. La ≤ 0 (black, or negative pixel values) has no
// logarithm and takes the lower plateau, which is the limit as La → 0.

double photopicTvi(double la) {
    if (!(la > 0)) return std::pow(10.0, -0.72);
    const double x = std::log10(la);
    double logTvi;
    if (x <= -2.6)
        logTvi = -0.72;
    else if (x >= 1.9)
        logTvi = x - 1.255;
    else
        logTvi = std::pow(0.249 * x + 0.65, 2.7) - 0.72;
    return std::pow(10.0, logTvi);
}

double scotopicTvi(double la) {
    if (!(la > 0)) return std::pow(10.0, -2.86);
    const double x = std::log10(la);
    double logTvi;
    if (x <= -3.94)
        logTvi = -2.86;
    else if (x >= -1.44)
        logTvi = x - 0.395;
    else
        logTvi = std::pow(0.405 * x + 1.6, 2.2) - 2.86;
    return std::pow(10.0, logTvi);
}

}  // namespace rr
