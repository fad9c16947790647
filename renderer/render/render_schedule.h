// Who decides how many samples each pixel gets and in what order pixels are visited.
//
// The render loop (renderer.h) asks a schedule for rounds. A round is a set of units of work
// that run in parallel; a unit visits its pixels in order on one thread, through a per-pixel
// hook (PixelRenderer) made for that unit, which may carry state from pixel to pixel. Plans
// depend on the settings and the film so far, never on the number of threads, and sample
// indices are given explicitly, so every image is bit-identical for any thread count.
// The schedules:
//  - UniformPasses: every pixel gets the same range of samples per round, progressively, until
//    the spp or the time limit is reached (path, path_mis, direct);
//  - ScanBands: fixed bands of rows, each scanned in order by one unit (TAIS: pixels learn
//    from the ones rendered before them);
//  - IteratedAllocation: per-pixel sample counts computed from the film after each round
//    (adaptive sampling such as PMC-IP's deterministic mixture).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "integrators/camera_ray.h"
#include "integrators/integrator.h"
#include "render/film.h"
#include "sampling/sampler.h"

namespace rr {

// One visit of a pixel: render samples [first, first + count) of pixel (x, y). Samples a
// technique renders only to learn from (TAIS's warm-up rows) have `keep` false and never reach
// the film.
struct PixelVisit {
    int x = 0, y = 0;
    uint32_t first = 0, count = 0;
    bool keep = true;
    bool operator==(const PixelVisit&) const = default;
};

// What a pixel hook produced for one visit: its sample values in sample order (cleared by the
// loop before each visit), and what a unit's visits cost. When the film splats samples into
// neighbouring pixels (recordOffsets), each value comes with its position in the pixel: hooks
// add values through add(), which records it from the sample that made the value.
struct PixelWork {
    std::vector<Rgb> values;
    std::vector<Vec2> offsets;  // with recordOffsets: values[i]'s position in its pixel
    bool recordOffsets = false;
    RayCounters rays;
    uint64_t nonFiniteSamples = 0;  // replaced by zero and reported: a bug indicator

    void add(const Rgb& value, const Camera& camera, const PixelSample& sample) {
        values.push_back(value);
        if (recordOffsets) offsets.push_back(filmOffset(camera, sample));
    }
};

// A sample value as the film takes it: non-finite values count as zero and are counted.
inline Rgb finiteOrZero(const Rgb& value, uint64_t* nonFinite) {
    if (value.isFinite()) return value;
    ++*nonFinite;
    return Rgb(0.0f);
}

// The per-pixel hook: renders the samples of a visit into work.values. A hook that chooses
// its own sample count (a technique with variable samples per pixel) may return another number
// of values than visit.count, numbered from visit.first on.
class PixelRenderer {
  public:
    virtual ~PixelRenderer() = default;
    virtual void render(const PixelVisit& visit, PixelWork& work) = 0;
};

// Timing the loop passes to a schedule planning its next round.
struct RoundTiming {
    double elapsed = 0;    // since the render started
    double timeLimit = 0;  // 0: none
    double lastRoundSeconds = 0;
    uint64_t lastRoundSamples = 0;  // kept samples of the last round
};

struct Round {
    size_t units = 0;
    // The loop may stop starting units when cancelled; the round, and the image, are then
    // incomplete. Otherwise a cancelled render finishes the round.
    bool interruptible = false;
};

class RenderSchedule {
  public:
    virtual ~RenderSchedule() = default;
    // Whether the render can stop at a time limit between rounds with a complete image.
    virtual bool supportsTimeLimit() const = 0;
    // Samples the whole render keeps, when known in advance (0: bounded by time only).
    virtual uint64_t plannedSamples() const = 0;
    // Plans the next round from the film so far; false when the image is complete.
    virtual bool nextRound(const Film& film, const RoundTiming& timing, Round* round) = 0;
    // The visits of unit `unit` of the current round, in order, into *visits (cleared first).
    virtual void unitVisits(size_t unit, std::vector<PixelVisit>* visits) const = 0;
    // A new per-pixel hook for one unit.
    virtual std::unique_ptr<PixelRenderer> pixelRenderer(const Sampler& sampler) const = 0;
};

// The hook of integrators whose samples are independent: each sample through estimate().
class SampleLoop final : public PixelRenderer {
  public:
    SampleLoop(const Scene& scene, const SampleIntegrator& integrator, const Sampler& sampler,
               int width)
        : scene_(scene), integrator_(integrator), sampler_(sampler), width_(width) {}

    void render(const PixelVisit& visit, PixelWork& work) override {
        const uint32_t pixel = uint32_t(visit.y) * uint32_t(width_) + uint32_t(visit.x);
        for (uint32_t s = visit.first; s < visit.first + visit.count; ++s) {
            const PixelSample sample = sampler_.at(pixel, s);
            work.add(integrator_.estimate(scene_, visit.x, visit.y, sample, work.rays),
                     scene_.camera(), sample);
        }
    }

  private:
    const Scene& scene_;
    const SampleIntegrator& integrator_;
    const Sampler& sampler_;
    int width_;
};

}  // namespace rr
