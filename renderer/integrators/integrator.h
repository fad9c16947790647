// Integrator interface: an unbiased (where claimed) estimate of one pixel sample. The render
// loop owns scheduling and accumulation; an integrator only turns sample coordinates into
// radiance, drawing every random number through the named decisions of PixelSample.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "math/rgb.h"
#include "sampling/sampler.h"
#include "scene/scene.h"

namespace rr {

// Rays traced, by kind; kept per tile and summed, for the rays-per-second report.
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

class Integrator {
  public:
    virtual ~Integrator() = default;
    virtual std::string name() const = 0;
    // Parameters as recorded in the output metadata.
    virtual nlohmann::json parameters() const = 0;
    virtual Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const = 0;
    // The most draws of one decision a pixel sample makes (DecisionSite::repeatCount).
    virtual uint32_t decisionRepeats() const { return 1; }
    // Whether the estimate accounts for participating media; the loader refuses a scene with
    // media for an integrator that would silently ignore them.
    virtual bool supportsMedia() const { return false; }
};

// The camera ray for pixel (x, y): film position, lens and shutter decisions are drawn only
// when the camera uses them.
Ray generateCameraRay(const Camera& camera, int x, int y, const PixelSample& sample);

// Emission found by a BSDF-sampled ray (density `bsdfPdf`) from `reference`, weighted against
// next-event estimation, whose density for the same light point or direction is
// `lightSelectPmf`·`lightPdf`. Without next-event estimation (or after a specular bounce)
// the emission counts in full.
float emissionMisWeight(bool countInFull, float bsdfPdf, float lightPdf);

// Radiance of the infinite lights along a ray that escaped the scene in direction `w`,
// MIS-weighted as emissionMisWeight() says; `reference` is where the ray started.
Rgb escapedRadiance(const Scene& scene, const Vec3& w, const Vec3& reference, bool countInFull,
                    float bsdfPdf);

// Veach's power heuristic (β = 2) for strategy a with nA samples against strategy b.
inline float powerHeuristic(float nA, float pdfA, float nB, float pdfB) {
    const float a = nA * pdfA, b = nB * pdfB;
    if (a == 0 || std::isinf(b)) return 0;
    const float r = b / a;  // overflow to infinity in r² correctly gives 0
    return 1.0f / (1.0f + r * r);
}

}  // namespace rr
