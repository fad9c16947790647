// Convergence rates: the least-squares slope of log(error) against log(spp), and against
// log(time), over a list of measurements. Natural logarithms; the slope does not depend on the
// base, the intercept does.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace rr {

struct ConvergencePoint {
    double spp = 0, error = 0;
    std::optional<double> time;  // seconds
};

// Ordinary least squares y = intercept + slope·x.
struct LineFit {
    double slope = 0;
    double slopeStderr = 0;  // sqrt(s²/Sxx), s² = RSS/(n−2)
    double intercept = 0;
    double r2 = 0;  // 1 − RSS/TSS; 1 when every y is equal (TSS = 0)
    size_t n = 0;
};

struct ConvergenceSlopes {
    LineFit vsSpp;
    std::optional<LineFit> vsTime;  // only when every point has a time
};

// Reads an array of points, or an object {"points": [...]}; each point is an object with
// "spp" > 0, "error" > 0 and optionally "time" > 0. Other keys are ignored, so points may carry
// labels. Throws MetricsError naming the JSON pointer of a bad value, e.g. /points/3/error.
std::vector<ConvergencePoint> parseConvergencePoints(const nlohmann::json& document);

// Throws MetricsError unless there are at least 3 points and x takes at least 2 distinct
// values; `xName` names x in that message.
LineFit fitLine(const std::vector<double>& x, const std::vector<double>& y,
                const std::string& xName);

// log(error) against log(spp), and against log(time) when every point has one.
ConvergenceSlopes convergenceSlopes(const std::vector<ConvergencePoint>& points);

}  // namespace rr
