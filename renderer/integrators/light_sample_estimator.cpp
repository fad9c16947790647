#include "integrators/light_sample_estimator.h"

namespace rr {

nlohmann::json LightSampleEstimator::parameters() const {
    return {{"type", name()}, {"light_samples", lightSamples_}};
}

}  // namespace rr
