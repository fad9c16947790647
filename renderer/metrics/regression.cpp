#include "metrics/regression.h"

#include <algorithm>
#include <cmath>

#include "metrics/metrics_error.h"

namespace rr {

namespace {

using Json = nlohmann::json;

double positiveNumber(const Json& point, const std::string& key, const std::string& pointer) {
    const Json& v = point.at(key);
    if (!v.is_number() || !std::isfinite(v.get<double>()) || !(v.get<double>() > 0))
        throw MetricsError(pointer + "/" + key + ": expected a positive number, got " + v.dump());
    return v.get<double>();
}

}  // namespace

std::vector<ConvergencePoint> parseConvergencePoints(const Json& document) {
    const bool wrapped = document.is_object() && document.contains("points");
    const Json& list = wrapped ? document["points"] : document;
    const std::string listPointer = wrapped ? "/points" : "";
    if (!list.is_array())
        throw MetricsError((wrapped ? listPointer : "/") +
                           ": expected an array of points or an object {\"points\": [...]}");
    std::vector<ConvergencePoint> points;
    for (size_t i = 0; i < list.size(); ++i) {
        const std::string pointer = listPointer + "/" + std::to_string(i);
        const Json& p = list[i];
        if (!p.is_object()) throw MetricsError(pointer + ": expected an object");
        for (const char* key : {"spp", "error"})
            if (!p.contains(key)) throw MetricsError(pointer + ": missing \"" + key + "\"");
        ConvergencePoint point{positiveNumber(p, "spp", pointer),
                               positiveNumber(p, "error", pointer), std::nullopt};
        if (p.contains("time")) point.time = positiveNumber(p, "time", pointer);
        points.push_back(point);
    }
    return points;
}

LineFit fitLine(const std::vector<double>& x, const std::vector<double>& y,
                const std::string& xName) {
    const size_t n = x.size();
    if (n < 3)
        throw MetricsError("too few points: " + std::to_string(n) +
                           " (a slope with a standard error needs at least 3)");
    const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
    if (*lo == *hi)
        throw MetricsError("every point has the same " + xName +
                           "; a slope needs at least 2 distinct values");
    double xMean = 0, yMean = 0;
    for (size_t i = 0; i < n; ++i) {
        xMean += x[i] / double(n);
        yMean += y[i] / double(n);
    }
    double sxx = 0, sxy = 0, tss = 0;
    for (size_t i = 0; i < n; ++i) {
        sxx += (x[i] - xMean) * (x[i] - xMean);
        sxy += (x[i] - xMean) * (y[i] - yMean);
        tss += (y[i] - yMean) * (y[i] - yMean);
    }
    LineFit fit;
    fit.n = n;
    fit.slope = sxy / sxx;
    fit.intercept = yMean - fit.slope * xMean;
    double rss = 0;
    for (size_t i = 0; i < n; ++i) {
        const double residual = y[i] - fit.intercept - fit.slope * x[i];
        rss += residual * residual;
    }
    fit.slopeStderr = std::sqrt(rss / double(n - 2) / sxx);
    fit.r2 = tss > 0 ? 1 - rss / tss : 1;
    return fit;
}

ConvergenceSlopes convergenceSlopes(const std::vector<ConvergencePoint>& points) {
    std::vector<double> logSpp, logTime, logError;
    for (const ConvergencePoint& p : points) {
        logSpp.push_back(std::log(p.spp));
        logError.push_back(std::log(p.error));
        if (p.time) logTime.push_back(std::log(*p.time));
    }
    ConvergenceSlopes slopes{fitLine(logSpp, logError, "spp"), std::nullopt};
    if (logTime.size() == points.size()) slopes.vsTime = fitLine(logTime, logError, "time");
    return slopes;
}

}  // namespace rr
