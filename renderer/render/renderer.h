// The render loop: asks a schedule (render_schedule.h) for rounds and runs each round's units in
// parallel on oneTBB, each unit's pixels in order through the unit's pixel hook, adding the
// kept samples to the film. With the box filter each pixel is only ever written by one unit per
// round, in sample order; a splatting film takes each unit's samples into a tile of its own and
// adds the tiles in unit order at the round's end (film.h). Either way the film is
// bit-identical for any thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "render/film.h"
#include "render/render_schedule.h"
#include "sampling/sampler.h"

namespace rr {

// Largest number of samples per pixel: the sample-count channel is a float (exact to 2^24),
// and structured samplers index a pixel's spp × repeats draws of a decision in 32 bits.
inline constexpr uint32_t kMaxSpp = 1u << 24;

struct RenderOptions {
    double timeLimit = 0;  // seconds (for progress; the schedule enforces it); 0: none
    uint32_t seed = 0;
    int threads = 0;  // 0: all cores
    SamplerType sampler = SamplerType::Independent;
    uint32_t samplerSetSize = 16;               // samples stratified together (spp when known)
    const std::atomic<bool>* cancel = nullptr;  // checked between rounds (and units, where the
                                                // round allows it)
};

struct RenderProgress {
    uint64_t samplesDone = 0;
    uint64_t samplesPlanned = 0;  // 0 when only time bounds the render
    double elapsed = 0;
    double timeLimit = 0;
    uint32_t sppDone = 0;  // samples per pixel of the complete rounds
};

struct RenderStats {
    uint32_t spp = 0;       // samples per pixel reached (their mean, for a variable allocation)
    bool complete = false;  // the film holds a complete image (at least one whole round)
    double seconds = 0;
    RayCounters rays;
    uint64_t nonFiniteSamples = 0;  // replaced by zero (and reported): a bug indicator
    bool interrupted = false;
};

using ProgressCallback = std::function<void(const RenderProgress&)>;

RenderStats render(RenderSchedule& schedule, const RenderOptions& options, Film& film,
                   const ProgressCallback& progress = {});

}  // namespace rr
