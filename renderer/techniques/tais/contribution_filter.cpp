#include "techniques/tais/contribution_filter.h"

#include <algorithm>
#include <vector>

namespace rr::tais {

int filterMaximumContribution(std::span<Rgb> samples) {
    const size_t n = samples.size();
    if (n == 0) return 0;
    std::vector<double> brightness(n);
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
        brightness[i] = std::max(0.0f, samples[i].luminance());
        sum += brightness[i];
    }
    const double factor = std::max(32.0 / double(n), 0.02);  // eq. (4)
    int clamped = 0;
    for (size_t i = 0; i < n; ++i) {
        const double limit = (sum - brightness[i]) * factor;
        if (brightness[i] <= limit) continue;
        samples[i] *= float(limit / brightness[i]);
        ++clamped;
    }
    return clamped;
}

}  // namespace rr::tais
