// The `two_stage` estimator as scenes name it (configs/README.md).
#include "config/json_reader.h"
#include "render/technique_registry.h"
#include "techniques/two_stage/two_stage_estimator.h"

namespace rr::two_stage {

namespace {

constexpr int64_t kMaxSamples = 4096;

std::unique_ptr<DirectLightingEstimator> makeEstimator(ObjectReader& json) {
    TwoStageSettings s;
    s.samples = static_cast<uint32_t>(json.getInt("samples", 1, Range::closed(1, kMaxSamples)));
    // The paper splits as many times as it takes samples; more simulates wavelet importance
    // sampling (fig. 12).
    s.splits =
        static_cast<uint32_t>(json.getInt("splits", s.samples, Range::closed(0, 64 * kMaxSamples)));
    s.peaks = json.getChoice("peaks", {"analytic", "bsdf"}, "analytic") == "bsdf"
                  ? PeakSource::BsdfSamples
                  : PeakSource::Analytic;
    return std::make_unique<TwoStageEstimator>(s);
}

}  // namespace

void registerTechnique(TechniqueRegistry& registry) {
    registry.addEstimator("two_stage", makeEstimator);
}

}  // namespace rr::two_stage
