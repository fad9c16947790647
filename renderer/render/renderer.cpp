#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <mutex>

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

// Runs unit `unit`: its visits in order through a new hook, the kept samples into the film.
void runUnit(RenderSchedule& schedule, size_t unit, const Sampler& sampler, Film& film,
             ProgressReporter& reporter, RoundTotals& totals, std::mutex& mutex) {
    std::vector<PixelVisit> visits;
    schedule.unitVisits(unit, &visits);
    const std::unique_ptr<PixelRenderer> hook = schedule.pixelRenderer(sampler);
    PixelWork work;
    uint64_t kept = 0;
    for (const PixelVisit& visit : visits) {
        work.values.clear();
        hook->render(visit, work);
        for (const Rgb& value : work.values) {
            const Rgb v = finiteOrZero(value, &work.nonFiniteSamples);
            if (visit.keep) film.add(visit.x, visit.y, v);
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
        arena.execute(
            [&] { totals = runRound(schedule, round, sampler, options, film, reporter); });
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
