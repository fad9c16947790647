#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <stdexcept>

namespace rr {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
}

// Throttled, thread-safe progress reporting from worker threads.
class ProgressReporter {
  public:
    ProgressReporter(const ProgressCallback& cb, Clock::time_point start, RenderProgress base)
        : callback_(cb), start_(start), base_(base) {}

    void addSamples(uint64_t n) {
        const uint64_t done = done_.fetch_add(n) + n;
        if (!callback_) return;
        const double now = secondsSince(start_);
        std::unique_lock lock(mutex_, std::try_to_lock);
        if (!lock.owns_lock() || now - lastReport_ < 0.2) return;
        lastReport_ = now;
        RenderProgress p = base_;
        p.samplesDone = done;
        p.elapsed = now;
        callback_(p);
    }
    void setSppDone(uint32_t spp) { base_.sppDone = spp; }

  private:
    const ProgressCallback& callback_;
    Clock::time_point start_;
    RenderProgress base_;
    std::atomic<uint64_t> done_{0};
    std::mutex mutex_;
    double lastReport_ = -1;
};

// What a round's units produced, summed.
struct RoundTotals {
    RayCounters rays;
    uint64_t nonFinite = 0, kept = 0;
    bool skipped = false;  // some unit did not run (cancelled)
};

bool cancelled(const RenderOptions& options) {
    return options.cancel && options.cancel->load();
}

// The pixels a unit keeps samples of, as a rectangle [x0, x1) × [y0, y1) (empty: none).
struct KeptBounds {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};
KeptBounds keptBounds(const std::vector<PixelVisit>& visits) {
    KeptBounds b{INT32_MAX, INT32_MAX, INT32_MIN, INT32_MIN};
    for (const PixelVisit& v : visits)
        if (v.keep) {
            b.x0 = std::min(b.x0, v.x);
            b.y0 = std::min(b.y0, v.y);
            b.x1 = std::max(b.x1, v.x + 1);
            b.y1 = std::max(b.y1, v.y + 1);
        }
    return b.x1 > b.x0 ? b : KeptBounds{};
}

// Runs unit `unit`: its visits in order through a new hook, the kept samples into the film
// (for a splatting film, into the unit's tile, which the round's end adds to the image).
void runUnit(RenderSchedule& schedule, size_t unit, const Sampler& sampler, Film& film,
             ProgressReporter& reporter, RoundTotals& totals, std::mutex& mutex) {
    std::vector<PixelVisit> visits;
    schedule.unitVisits(unit, &visits);
    const std::unique_ptr<PixelRenderer> hook = schedule.pixelRenderer(sampler);
    SplatTile* tile = nullptr;
    if (film.splats()) {
        const KeptBounds b = keptBounds(visits);
        tile = &film.openTile(unit, b.x0, b.y0, b.x1, b.y1);
    }
    PixelWork work;
    work.recordOffsets = tile != nullptr;
    uint64_t kept = 0;
    for (const PixelVisit& visit : visits) {
        work.values.clear();
        work.offsets.clear();
        hook->render(visit, work);
        if (tile && visit.keep && work.offsets.size() != work.values.size())
            throw std::logic_error("a pixel hook gave values without their film positions");
        for (size_t i = 0; i < work.values.size(); ++i) {
            const Rgb v = finiteOrZero(work.values[i], &work.nonFiniteSamples);
            if (!visit.keep) continue;
            if (tile) {
                tile->add(film.filter(), visit.x, visit.y, work.offsets[i], v);
                film.countSample(visit.x, visit.y);
            } else {
                film.add(visit.x, visit.y, v);
            }
        }
        if (visit.keep) kept += work.values.size();
    }
    reporter.addSamples(kept);
    std::lock_guard lock(mutex);
    totals.rays += work.rays;
    totals.nonFinite += work.nonFiniteSamples;
    totals.kept += kept;
}

RoundTotals runRound(RenderSchedule& schedule, const Round& round, const Sampler& sampler,
                     const RenderOptions& options, Film& film, ProgressReporter& reporter) {
    RoundTotals totals;
    std::mutex mutex;
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, round.units, 1),
        [&](const tbb::blocked_range<size_t>& range) {
            for (size_t unit = range.begin(); unit != range.end(); ++unit) {
                if (round.interruptible && cancelled(options)) {
                    std::lock_guard lock(mutex);
                    totals.skipped = true;
                    return;
                }
                runUnit(schedule, unit, sampler, film, reporter, totals, mutex);
            }
        },
        tbb::simple_partitioner());
    return totals;
}

}  // namespace

RenderStats render(RenderSchedule& schedule, const RenderOptions& options, Film& film,
                   const ProgressCallback& progress) {
    const Sampler sampler(options.sampler, options.seed, options.samplerSetSize);
    const uint64_t pixels = uint64_t(film.width()) * film.height();
    const Clock::time_point start = Clock::now();
    ProgressReporter reporter(
        progress, start, RenderProgress{0, schedule.plannedSamples(), 0, options.timeLimit, 0});
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);

    RenderStats stats;
    uint64_t kept = 0;
    RoundTiming timing{0, options.timeLimit, 0, 0};
    for (;;) {
        Round round;
        timing.elapsed = secondsSince(start);
        if (!schedule.nextRound(film, timing, &round)) break;
        if (cancelled(options)) {
            stats.interrupted = true;
            break;
        }
        const Clock::time_point roundStart = Clock::now();
        RoundTotals totals;
        if (film.splats()) film.beginRound(round.units);
        arena.execute([&] {
            totals = runRound(schedule, round, sampler, options, film, reporter);
            film.endRound();
        });
        stats.rays += totals.rays;
        stats.nonFiniteSamples += totals.nonFinite;
        kept += totals.kept;
        if (totals.skipped) {
            stats.interrupted = true;
            stats.complete = false;
            break;
        }
        // A round that keeps no samples (a technique's pilot) completes no image.
        if (kept > 0) stats.complete = true;
        timing.lastRoundSeconds = secondsSince(roundStart);
        timing.lastRoundSamples = totals.kept;
        reporter.setSppDone(static_cast<uint32_t>(kept / pixels));
    }
    stats.spp = stats.complete ? static_cast<uint32_t>(kept / pixels) : 0;
    stats.seconds = secondsSince(start);
    return stats;
}

}  // namespace rr
