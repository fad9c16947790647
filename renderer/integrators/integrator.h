// Integrator interface. An integrator turns the sample coordinates of a pixel into radiance,
// drawing every random number through the named decisions of PixelSample; the render loop
// (render/) decides how many samples each pixel gets and in what order, through a schedule.
//  - Integrator: what every integrator reports and checks (name, parameters, media support,
//    its choices resolved against the scene);
//  - SampleIntegrator: integrators whose pixel samples are independent estimates, rendered in
//    any order on any thread (path, path_mis, direct).
// Techniques whose pixels learn from each other (TAIS) derive from Integrator and supply their
// own schedule and per-pixel hook (render/render_schedule.h).
#pragma once

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "math/rgb.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace rr {

// Rays traced, by kind; kept per unit of work and summed, for the rays-per-second report.
struct RayCounters {
    uint64_t camera = 0;
    uint64_t extension = 0;  // bounce rays after the camera ray
    uint64_t shadow = 0;
    uint64_t total() const { return camera + extension + shadow; }
    RayCounters& operator+=(const RayCounters& o) {
        camera += o.camera;
        extension += o.extension;
        shadow += o.shadow;
        return *this;
    }
};

// A per-pixel image an integrator computes besides radiance (RIS's optimal M/N), written as an
// extra channel of the output; `values` row-major, one per pixel.
struct AuxiliaryChannel {
    std::string name;
    std::string description;
    std::vector<float> values;
};

// Pixel values and the variance of each, row-major, one per pixel (empty: none).
struct PixelEstimates {
    std::vector<Rgb> values;
    std::vector<Rgb> variances;
};

// What light an integrator's image holds: light reaching the camera after one reflection from
// the lights (direct lighting), or along paths of every length the scene's path settings allow.
// Two integrators estimate the same image only if they agree on it (the cross-paper matrix
// compares only those: experiments/harness/matrix_configs.py).
enum class LightTransport : uint8_t { Direct, Paths };

inline const char* transportName(LightTransport transport) {
    return transport == LightTransport::Direct ? "direct" : "paths";
}

class Integrator {
  public:
    virtual ~Integrator() = default;
    // The type it is registered under (render/technique_registry.h), as scenes name it.
    virtual std::string name() const = 0;
    virtual LightTransport transport() const = 0;
    // Whether it draws points on lights (next-event estimation); one that does not finds
    // emitters only by hitting them, so point and spot lights never reach its image, which
    // then estimates another image than the scene's (`renderer check --json`'s
    // unreachableLights).
    virtual bool samplesLights() const { return true; }
    // Parameters as recorded in the output metadata: readParameters() and what the
    // integrator resolved from them.
    virtual nlohmann::json parameters() const = 0;
    // The keys of its JSON object as the registry read them (its table's keys, defaults
    // filled in), with its "type".
    void setReadParameters(nlohmann::json values) { readParameters_ = std::move(values); }
    nlohmann::json readParameters() const {
        nlohmann::json p = readParameters_;
        p["type"] = name();
        return p;
    }
    // The most draws of one decision a pixel sample makes (DecisionSite::repeatCount).
    virtual uint32_t decisionRepeats() const { return 1; }
    // Called by the loader once the scene is built, before any rendering: an integrator that
    // adapts to the scene's contents resolves its choices here (and throws ConfigError for a
    // choice the scene cannot support).
    virtual void prepare(const Scene& /*scene*/) {}
    // Values for keys of its JSON object that make a render depend only on the scene, seed and
    // spp, for an integrator whose choices follow what it measures (RIS's pilot times its
    // candidates): a render's fingerprint (`renderer check --json`, "pinned") sets them. Empty
    // when the render is reproducible as configured.
    virtual nlohmann::json pinnedSettings() const { return nlohmann::json::object(); }
    // Channels besides radiance, once the render is done.
    virtual std::vector<AuxiliaryChannel> auxiliaryChannels() const { return {}; }
    // Whether the image is pixelEstimates(), formed from the integrator's own record of its
    // samples (PMC-IP weights each sample by its sampling density), so that the film only
    // counts them.
    virtual bool formsOwnImage() const { return false; }
    // Once the render is done: the pixel estimates when the integrator forms its own image;
    // else empty.
    virtual PixelEstimates pixelEstimates() const { return {}; }

  private:
    nlohmann::json readParameters_ = nlohmann::json::object();
};

class SampleIntegrator : public Integrator {
  public:
    // Called when a width × height render is scheduled, before any estimate(): an integrator
    // that keeps per-pixel records sizes them here. `iterated`: the schedule renders in
    // iterations and calls commitPixelRecords() between them.
    virtual void beginImage(int /*width*/, int /*height*/, bool /*iterated*/) {}
    // Between the iterations of a schedule that renders in iterations (PMC-IP): the per-pixel
    // records so far become what the next iteration's estimates start from (pixel_records.h).
    virtual void commitPixelRecords() {}
    virtual Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const = 0;
};

// Veach's power heuristic (β = 2) for strategy a with nA samples against strategy b.
inline float powerHeuristic(float nA, float pdfA, float nB, float pdfB) {
    const float a = nA * pdfA, b = nB * pdfB;
    if (a == 0 || std::isinf(b)) return 0;
    const float r = b / a;  // overflow to infinity in r² correctly gives 0
    return 1.0f / (1.0f + r * r);
}

// Radiance of the infinite lights along a ray that escaped the scene in direction `w`, each
// light's weighted by `weightOf(light)` (1 for a camera ray, which no other strategy could have
// found; an MIS weight for a scattered ray).
template <class WeightOf>
Rgb escapedRadiance(const Scene& scene, const Vec3& w, const WeightOf& weightOf) {
    Rgb sum(0.0f);
    for (const Light* light : scene.infiniteLights()) {
        const Rgb le = light->escapedRadiance(w);
        if (le.isBlack()) continue;
        sum += le * weightOf(*light);
    }
    return sum;
}

}  // namespace rr
