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
#include "render/film.h"
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
    // The most draws of one decision a pixel sample makes (DecisionSite::repeatCount).
    virtual uint32_t decisionRepeats() const { return 1; }
    // Whether the estimate accounts for participating media; the loader refuses a scene with
    // media for an integrator that would silently ignore them.
    virtual bool supportsMedia() const { return false; }
    // Called by the loader once the scene is built, before any rendering: an integrator that
    // adapts to the scene's contents resolves its choices here (and throws ConfigError for a
    // choice the scene cannot support).
    virtual void prepare(const Scene& /*scene*/) {}
};

// Integrators whose pixel samples are independent: the render loop schedules them in
// progressive passes, in any order and on any thread.
class SampleIntegrator : public Integrator {
  public:
    virtual Rgb estimate(const Scene& scene, int x, int y, const PixelSample& sample,
                         RayCounters& rays) const = 0;
};

// Integrators whose pixels learn from the pixels rendered before them (TAIS): each band of
// rows is rendered in the integrator's own order with a fixed number of samples per pixel; the
// render loop runs bands in parallel. Bands are fixed by the integrator, not by the thread
// count, so the image is the same for any number of threads.
class BandIntegrator : public Integrator {
  public:
    virtual int bandRows() const = 0;
    struct BandResult {
        RayCounters rays;
        uint64_t nonFiniteSamples = 0;  // dropped (counted as zero) and reported
    };
    // Renders rows [y0, y1) of `film` with `spp` samples per pixel.
    virtual BandResult renderBand(const Scene& scene, const Sampler& sampler, int y0, int y1,
                                  uint32_t spp, Film& film) const = 0;
};

// The camera ray for pixel (x, y): film position, lens and shutter decisions are drawn only
// when the camera uses them.
Ray generateCameraRay(const Camera& camera, int x, int y, const PixelSample& sample);

// Emission found by a BSDF-sampled ray (density `bsdfPdf`) from `reference`, weighted against
// next-event estimation, whose density for the same light point or direction is
// `lightSelectPmf`·`lightPdf`. Without next-event estimation (or after a specular bounce)
// the emission counts in full.
float emissionMisWeight(bool countInFull, float bsdfPdf, float lightPdf);

// Veach's power heuristic (β = 2) for strategy a with nA samples against strategy b.
inline float powerHeuristic(float nA, float pdfA, float nB, float pdfB) {
    const float a = nA * pdfA, b = nB * pdfB;
    if (a == 0 || std::isinf(b)) return 0;
    const float r = b / a;  // overflow to infinity in r² correctly gives 0
    return 1.0f / (1.0f + r * r);
}

// Radiance of the infinite lights along a ray that escaped the scene in direction `w`, each
// light MIS-weighted as emissionMisWeight() says, with `lightPdf(light)` the density with which
// next-event estimation from the ray's origin would have chosen that light and direction.
template <class LightPdf>
Rgb escapedRadiance(const Scene& scene, const Vec3& w, bool countInFull, float bsdfPdf,
                    const LightPdf& lightPdf) {
    Rgb sum(0.0f);
    for (const Light* light : scene.infiniteLights()) {
        const Rgb le = light->escapedRadiance(w);
        if (le.isBlack()) continue;
        sum += le * emissionMisWeight(countInFull, bsdfPdf, countInFull ? 0.0f : lightPdf(*light));
    }
    return sum;
}

// The same counted in full (a camera ray, which no other strategy could have found).
inline Rgb escapedRadiance(const Scene& scene, const Vec3& w) {
    return escapedRadiance(scene, w, true, 0, [](const Light&) { return 0.0f; });
}

}  // namespace rr
