// The render loop: progressive passes over 16×16 tiles in parallel (oneTBB). A pass adds the
// same range of sample indices to every pixel, so every pixel always holds the same number of
// samples and an image can be saved after any pass. Passes grow to about a second each; with
// a time limit, a pass starts only if it is predicted to finish in time.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "integrators/integrator.h"
#include "render/film.h"
#include "sampling/sampler.h"

namespace rr {

// Largest number of samples per pixel: the sample-count channel is a float (exact to 2^24),
// and structured samplers index a pixel's spp × repeats draws of a decision in 32 bits.
inline constexpr uint32_t kMaxSpp = 1u << 24;

struct RenderOptions {
    uint32_t spp = 16;     // target; with a time limit, an upper bound (0: none)
    double timeLimit = 0;  // seconds; 0: render exactly spp
    uint32_t seed = 0;
    int threads = 0;  // 0: all cores
    SamplerType sampler = SamplerType::Independent;
    uint32_t samplerSetSize = 16;               // samples stratified together (spp when known)
    const std::atomic<bool>* cancel = nullptr;  // checked between passes
};

struct RenderProgress {
    uint64_t samplesDone = 0;
    uint64_t samplesPlanned = 0;  // 0 when only time bounds the render
    double elapsed = 0;
    double timeLimit = 0;
    uint32_t sppDone = 0;
};

struct RenderStats {
    uint32_t spp = 0;  // samples per pixel reached
    double seconds = 0;
    RayCounters rays;
    uint64_t nonFiniteSamples = 0;  // dropped (and reported): a bug indicator, never silent
    bool interrupted = false;
};

using ProgressCallback = std::function<void(const RenderProgress&)>;

RenderStats render(const Scene& scene, const Integrator& integrator, const RenderOptions& options,
                   Film& film, const ProgressCallback& progress = {});

}  // namespace rr
