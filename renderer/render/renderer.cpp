#include "render/renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace rr {

namespace {

constexpr int kTileSize = 16;
constexpr double kTargetPassSeconds = 1.0;

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

// Independent samples: progressive passes over tiles.
RenderStats renderPasses(const Scene& scene, const SampleIntegrator& integrator,
                         const RenderOptions& options, Film& film,
                         const ProgressCallback& progress) {
    const int width = film.width(), height = film.height();
    const int tilesX = (width + kTileSize - 1) / kTileSize;
    const int tilesY = (height + kTileSize - 1) / kTileSize;
    const Sampler sampler(options.sampler, options.seed, options.samplerSetSize);
    const uint64_t pixels = uint64_t(width) * height;

    RenderStats stats;
    std::atomic<uint64_t> camera{0}, extension{0}, shadow{0}, nonFinite{0};
    const Clock::time_point start = Clock::now();
    ProgressReporter reporter(progress, start,
                              RenderProgress{0, options.timeLimit > 0 ? 0 : pixels * options.spp, 0,
                                             options.timeLimit, 0});

    // A pass renders sample indices [first, first + count) of every pixel.
    auto runPass = [&](uint32_t first, uint32_t count) {
        tbb::parallel_for(
            tbb::blocked_range<int>(0, tilesX * tilesY, 1),
            [&](const tbb::blocked_range<int>& range) {
                RayCounters rays;
                uint64_t bad = 0;
                for (int tile = range.begin(); tile != range.end(); ++tile) {
                    const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
                    const int x1 = std::min(x0 + kTileSize, width);
                    const int y1 = std::min(y0 + kTileSize, height);
                    for (int y = y0; y < y1; ++y)
                        for (int x = x0; x < x1; ++x) {
                            const uint32_t pixel = uint32_t(y) * uint32_t(width) + uint32_t(x);
                            for (uint32_t s = first; s < first + count; ++s) {
                                const Rgb v =
                                    integrator.estimate(scene, x, y, sampler.at(pixel, s), rays);
                                if (v.isFinite()) {
                                    film.add(x, y, v);
                                } else {
                                    ++bad;
                                    film.add(x, y, Rgb(0.0f));
                                }
                            }
                        }
                    reporter.addSamples(uint64_t(x1 - x0) * (y1 - y0) * count);
                }
                camera += rays.camera;
                extension += rays.extension;
                shadow += rays.shadow;
                nonFinite += bad;
            },
            tbb::simple_partitioner());
    };

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    const uint32_t cap = options.spp > 0 ? options.spp : UINT32_MAX;
    uint32_t done = 0, passSize = 1;
    double secondsPerSpp = 0;
    while (done < cap) {
        if (options.cancel && options.cancel->load()) {
            stats.interrupted = true;
            break;
        }
        uint32_t count = std::min(passSize, cap - done);
        if (options.timeLimit > 0 && done > 0) {
            const double remaining = options.timeLimit - secondsSince(start);
            const double affordable = std::floor(remaining / secondsPerSpp);
            if (affordable < 1) break;
            count = static_cast<uint32_t>(std::min<double>(count, affordable));
        }
        const Clock::time_point passStart = Clock::now();
        arena.execute([&] { runPass(done, count); });
        done += count;
        reporter.setSppDone(done);
        secondsPerSpp = std::max(secondsSince(passStart) / count, 1e-9);
        const double target = options.timeLimit > 0
                                  ? std::min(kTargetPassSeconds, options.timeLimit / 8)
                                  : kTargetPassSeconds;
        passSize = static_cast<uint32_t>(
            std::clamp(target / secondsPerSpp, 1.0, 2.0 * std::max<uint32_t>(count, 1)));
    }

    stats.spp = done;
    stats.seconds = secondsSince(start);
    stats.rays = RayCounters{camera.load(), extension.load(), shadow.load()};
    stats.nonFiniteSamples = nonFinite.load();
    return stats;
}

// Bands of rows, each rendered in the integrator's order, in parallel; one pass of all samples.
RenderStats renderBands(const Scene& scene, const BandIntegrator& integrator,
                        const RenderOptions& options, Film& film,
                        const ProgressCallback& progress) {
    if (options.timeLimit > 0)
        throw std::invalid_argument(integrator.name() + " cannot render to a time limit");
    const int height = film.height(), rows = integrator.bandRows();
    const int bands = (height + rows - 1) / rows;
    const Sampler sampler(options.sampler, options.seed, options.samplerSetSize);
    const Clock::time_point start = Clock::now();
    ProgressReporter reporter(
        progress, start, RenderProgress{0, uint64_t(film.width()) * height * options.spp, 0, 0, 0});
    std::mutex mutex;
    RenderStats stats;
    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        tbb::parallel_for(
            tbb::blocked_range<int>(0, bands, 1),
            [&](const tbb::blocked_range<int>& range) {
                for (int band = range.begin(); band != range.end(); ++band) {
                    if (options.cancel && options.cancel->load()) return;
                    const int y0 = band * rows, y1 = std::min(y0 + rows, height);
                    const BandIntegrator::BandResult r =
                        integrator.renderBand(scene, sampler, y0, y1, options.spp, film);
                    {
                        std::lock_guard lock(mutex);
                        stats.rays += r.rays;
                        stats.nonFiniteSamples += r.nonFiniteSamples;
                    }
                    reporter.addSamples(uint64_t(film.width()) * (y1 - y0) * options.spp);
                }
            },
            tbb::simple_partitioner());
    });
    stats.interrupted = options.cancel && options.cancel->load();
    stats.spp = stats.interrupted ? 0 : options.spp;
    stats.seconds = secondsSince(start);
    return stats;
}

}  // namespace

RenderStats render(const Scene& scene, const Integrator& integrator, const RenderOptions& options,
                   Film& film, const ProgressCallback& progress) {
    if (const auto* bands = dynamic_cast<const BandIntegrator*>(&integrator))
        return renderBands(scene, *bands, options, film, progress);
    return renderPasses(scene, dynamic_cast<const SampleIntegrator&>(integrator), options, film,
                        progress);
}

}  // namespace rr
