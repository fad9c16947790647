// Direct-lighting estimator interface: the light that emitters send to a shading point and the
// point scatters towards the viewer. One implementation of next-event estimation serves both
// the `direct` integrator and every vertex of the path walk; estimators are chosen by name in
// the scene's integrator ("strategy" or "estimator"; configs/README.md).
//  - light: light sampling only;
//  - bsdf: no light samples: emission is found by the integrator's own BSDF (or phase)
//    samples and counts in full;
//  - mis: light sampling combined with the integrator's scattering samples by the power
//    heuristic (Veach & Guibas 1995).
// Techniques add more (resampled importance sampling, two-stage sampling of environment maps)
// through the technique registry.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "integrators/integrator.h"
#include "integrators/pixel_records.h"
#include "integrators/shading_point.h"

namespace rr {

// How emission that the integrator's own scattering sample finds counts against the estimate.
enum class FoundEmission : uint8_t {
    Full,      // the estimate does not cover it (no light samples)
    Weighted,  // MIS: weighted against the estimate's light samples
    Excluded,  // the estimate covers all of it: finding it again would count it twice
};

class LightSampleEstimator;

class DirectLightingEstimator {
  public:
    virtual ~DirectLightingEstimator() = default;
    virtual std::string name() const = 0;
    // Parameters as recorded in the output metadata (merged into the integrator's):
    // readParameters() and what the estimator resolved from them.
    virtual nlohmann::json parameters() const = 0;
    // The keys of its JSON object as the registry read them, with its "type".
    void setReadParameters(nlohmann::json values) { readParameters_ = std::move(values); }
    nlohmann::json readParameters() const {
        nlohmann::json p = readParameters_;
        p["type"] = name();
        return p;
    }
    // Light samples per estimate (0: the estimate is always zero and need not be asked).
    virtual uint32_t lightSamples() const = 0;
    virtual FoundEmission foundEmission() const = 0;
    // The most draws of one decision an estimate makes (DecisionSite::repeatCount).
    virtual uint32_t decisionRepeats() const { return lightSamples(); }
    // False for estimators that sample directions and find emission along them
    // (ShadingPoint::incidentEmission), which scenes with media do not provide.
    virtual bool worksInMedia() const { return true; }
    // Whether it draws points on lights; one that does not finds emitters only by hitting
    // them, so a point or spot light (a delta light) never reaches its estimate.
    virtual bool samplesLights() const { return lightSamples() > 0; }
    // The fields the estimator records per pixel at first hits (ShadingPoint::record), which
    // the `direct` and `path_mis` integrators average over each pixel's samples and write as
    // channels of these names; no names: none.
    virtual PixelRecordLayout pixelRecords() const { return {}; }

    // Called once the scene is built, before rendering: an estimator that needs something of
    // the scene builds it here (two-stage sampling's summed-area table), and throws ConfigError
    // at `pointer` (the estimator's JSON object) for a scene it cannot render.
    virtual void prepare(const Scene& /*scene*/, const std::string& /*pointer*/) {}

    // Estimates the direct light at `point` towards the viewer, adding each sample's
    // contribution to the point (ShadingPoint::add).
    virtual void estimate(ShadingPoint& point) const = 0;

    // This estimator as light sampling (`light`, `mis`), or nullptr: the common case, which
    // runEstimator() calls without the interface's indirection.
    const LightSampleEstimator* lightSampling() const { return lightSampling_; }

    DirectLightingEstimator(const DirectLightingEstimator&) = delete;
    DirectLightingEstimator& operator=(const DirectLightingEstimator&) = delete;

  protected:
    DirectLightingEstimator() = default;
    explicit DirectLightingEstimator(const LightSampleEstimator* self) : lightSampling_(self) {}

  private:
    const LightSampleEstimator* lightSampling_ = nullptr;
    nlohmann::json readParameters_ = nlohmann::json::object();
};

// The weight of emission found by `scatterSamples` scattering samples of density `scatterPdf`,
// against `estimator`; `lightPdf()` gives the density with which the estimator's light
// sampling picks the same light point or direction (asked only for MIS). Specular samples and
// the camera ray (`inFull`) count in full: no light sample can find what they find.
template <class LightPdf>
float foundEmissionWeight(const DirectLightingEstimator& estimator, bool inFull,
                          float scatterSamples, float scatterPdf, const LightPdf& lightPdf) {
    if (inFull) return 1;
    switch (estimator.foundEmission()) {
        case FoundEmission::Full:
            return 1;
        case FoundEmission::Weighted:
            return powerHeuristic(scatterSamples, scatterPdf,
                                  static_cast<float>(estimator.lightSamples()), lightPdf());
        case FoundEmission::Excluded:
            break;
    }
    return 0;
}

}  // namespace rr
