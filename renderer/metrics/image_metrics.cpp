#include "metrics/image_metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "math/tvi.h"
#include "metrics/metrics_error.h"

namespace rr {

namespace {

std::vector<double> luminance(const InputImage& image) {
    std::vector<double> y(image.pixels());
    for (size_t i = 0; i < y.size(); ++i)
        y[i] = 0.2126 * image.channels[0][i] + 0.7152 * image.channels[1][i] +
               0.0722 * image.channels[2][i];
    return y;
}

// Mean of `values` without the floor(fraction·n) largest.
double meanWithoutLargest(std::vector<double> values, double fraction) {
    const size_t keep = values.size() - size_t(std::floor(fraction * double(values.size())));
    std::nth_element(values.begin(), values.begin() + keep - 1, values.end());
    return std::accumulate(values.begin(), values.begin() + keep, 0.0) / double(keep);
}

// Everything but tviErr, over `x` against `r`: one vector of per-pixel values per channel.
ErrorStats errorStats(const std::vector<const std::vector<double>*>& x,
                      const std::vector<const std::vector<double>*>& r, double rejectFraction) {
    const size_t pixels = r[0]->size();
    double squared = 0, referenceSum = 0, imageSum = 0;
    std::vector<double> relmsePerPixel(pixels, 0.0);
    for (size_t c = 0; c < r.size(); ++c)
        for (size_t i = 0; i < pixels; ++i) {
            const double ref = (*r[c])[i], d = (*x[c])[i] - ref;
            squared += d * d;
            referenceSum += ref;
            imageSum += (*x[c])[i];
            relmsePerPixel[i] += d * d / (ref * ref + 0.01) / double(r.size());
        }
    ErrorStats s;
    const double values = double(pixels) * double(r.size());
    s.mse = squared / values;
    s.rmse = std::sqrt(s.mse);
    s.referenceMean = referenceSum / values;
    s.mean = imageSum / values;
    if (s.referenceMean > 0) {
        s.sigmaOverMu = s.rmse / s.referenceMean;
        s.relativeBias = s.mean / s.referenceMean - 1;
    }
    s.relmse = meanWithoutLargest(std::move(relmsePerPixel), rejectFraction);
    return s;
}

// (1/N) Σ (S·(x−r))² / tvi(S·L), S the display scale and L the reference luminance.
double tviError(const std::vector<double>& x, const std::vector<double>& r,
                const std::vector<double>& referenceLuminance, double cdPerUnit) {
    double sum = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double e = (x[i] - r[i]) * cdPerUnit;
        sum += e * e / photopicTvi(referenceLuminance[i] * cdPerUnit);
    }
    return sum / double(x.size());
}

void checkInputs(const InputImage& image, const InputImage& reference, const CompareOptions& o) {
    if (!(o.relmseRejectFraction >= 0 && o.relmseRejectFraction < 0.5))
        throw MetricsError("the relMSE rejection fraction (--relmse-reject) must be in [0, 0.5)");
    if (!(std::isfinite(o.cdPerUnit) && o.cdPerUnit > 0))
        throw MetricsError("the display scale (--cd-per-unit) must be a positive number");
    if (image.width != reference.width || image.height != reference.height)
        throw MetricsError(image.source + " is " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + " but the reference " + reference.source +
                           " is " + std::to_string(reference.width) + "x" +
                           std::to_string(reference.height));
}

}  // namespace

Comparison compareImages(const InputImage& image, const InputImage& reference,
                         const CompareOptions& options) {
    checkInputs(image, reference, options);
    const double reject = options.relmseRejectFraction;
    Comparison c;
    c.width = image.width;
    c.height = image.height;
    const auto& x = image.channels;
    const auto& r = reference.channels;
    c.rgb = errorStats({&x[0], &x[1], &x[2]}, {&r[0], &r[1], &r[2]}, reject);
    if (!(c.rgb.referenceMean > 0 && std::isfinite(c.rgb.referenceMean)))
        throw MetricsError("the reference " + reference.source + " has mean " +
                           messageNumber(c.rgb.referenceMean) +
                           " over R, G, B; sigma/mu needs a positive mean");

    const std::vector<double> yImage = luminance(image), yReference = luminance(reference);
    const double s = options.cdPerUnit;
    for (size_t k = 0; k < 3; ++k) {
        c.channels[k] = errorStats({&x[k]}, {&r[k]}, reject);
        c.channels[k].tviErr = tviError(x[k], r[k], yReference, s);
    }
    c.luminance = errorStats({&yImage}, {&yReference}, reject);
    c.luminance.tviErr = tviError(yImage, yReference, yReference, s);
    c.rgb.tviErr = c.luminance.tviErr;
    return c;
}

std::optional<double> efficiency(double error, double seconds) {
    const double e = 1 / (seconds * error);
    return std::isfinite(e) ? std::optional<double>(e) : std::nullopt;
}

}  // namespace rr
