#include "techniques/pmc/pmc_ip_integrator.h"

#include <chrono>
#include <stdexcept>

#include "config/config_error.h"
#include "math/tvi.h"
#include "render/renderer.h"
#include "sampling/hash.h"
#include "techniques/pmc/mixture_allocation.h"

namespace rr::pmc {

namespace {

// The residual draw's offset for iteration t: one uniform per iteration, from the seed.
double residualOffset(uint32_t seed, int iteration) {
    constexpr uint64_t kResidualTag = 0x706d635f6970;  // "pmc_ip"
    return double(hashKeys(kResidualTag, seed, uint64_t(iteration)) >> 11) * 0x1p-53;
}

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

PmcIpIntegrator::PmcIpIntegrator(std::unique_ptr<SampleIntegrator> pixelIntegrator,
                                 const PmcIpSettings& settings)
    : pixelIntegrator_(std::move(pixelIntegrator)), settings_(settings) {
    if (settings_.initialSpp < 2 || settings_.iterationSpp < 1)
        throw std::logic_error("pmc_ip needs two initial samples per pixel and iterations of one");
}

nlohmann::json PmcIpIntegrator::parameters() const {
    nlohmann::json p = readParameters();
    p["integrator"] = pixelIntegrator_->parameters();
    const int completed = iterationsDone_ + (currentIterationRan() && !pilot_ ? 1 : 0);
    if (completed > 0) {
        p["iterations"] = completed;
        p["adapt_seconds"] = adaptSeconds_;
    }
    return p;
}

std::unique_ptr<RenderSchedule> PmcIpIntegrator::schedule(const ScheduleInputs& in) {
    pixelIntegrator_->beginImage(in.width, in.height, /*iterated=*/true);
    const uint64_t pixels = uint64_t(in.width) * uint64_t(in.height);
    const uint32_t initial = settings_.initialSpp, step = settings_.iterationSpp;
    if (settings_.knownVarianceSpp > 0) {
        if (in.timeLimit > 0)
            throw ConfigError("/integrator/known_variance_spp",
                              "the static allocation spreads the spp it is given at once; "
                              "--time-limit cannot stop it part-way (use --spp)");
        maxIterations_ = 1;
    } else {
        if (in.spp < initial)
            throw ConfigError("/render/spp", "pmc_ip renders " + std::to_string(initial) +
                                                 " initial samples per pixel; " +
                                                 std::to_string(in.spp) + " spp is fewer");
        // Iterations of `step` samples per pixel, the last taking what is left of the spp.
        maxIterations_ = int((in.spp - initial + step - 1) / step);
        lastIterationSpp_ = in.spp - initial - (maxIterations_ - 1) * step;
    }
    width_ = in.width;
    seed_ = in.seed;
    spp_ = in.spp;
    iterationsDone_ = 0;
    planned_ = false;
    pilot_ = false;
    ran_ = false;
    adaptSeconds_ = 0;
    record_.emplace(in.width, in.height, ReconstructionFilter(in.filter));
    alpha_.assign(pixels, 1.0 / double(pixels));
    variance_.assign(pixels, 0.0);
    control_.assign(pixels, Rgb(0.0f));
    estimates_.assign(pixels, EstimateMoments{});
    image_ = {};
    return std::make_unique<IteratedAllocation>(
        in.scene, *pixelIntegrator_, in.width, in.height, in.timeLimit,
        [this](const Film&, int iteration, IteratedAllocation::Plan* plan) {
            completeIteration();
            const bool more = settings_.knownVarianceSpp > 0
                                  ? allocateKnownVariance(iteration, plan)
                                  : allocate(iteration, plan);
            planned_ = more;
            ran_ = false;
            return more;
        },
        [this](const PixelVisit& visit, const std::vector<Rgb>& values,
               const std::vector<Vec2>& offsets) { observe(visit, values, offsets); },
        [this] { finish(); });
}

bool PmcIpIntegrator::allocate(int iteration, IteratedAllocation::Plan* plan) {
    if (iteration > maxIterations_) return false;
    if (iteration == 0) {
        plan->counts.assign(record_->pixels(), settings_.initialSpp);
        record_->beginIteration(plan->counts,
                                std::vector<double>(record_->pixels(), settings_.initialSpp),
                                /*pilot=*/false);
    } else {
        adapt(plan);
    }
    return true;
}

void PmcIpIntegrator::drawCounts(uint64_t total, IteratedAllocation::Plan* plan) const {
    plan->counts.resize(alpha_.size());
    mixtureCounts(alpha_, total, residualOffset(seed_, iterationsDone_), plan->counts);
}

// §4.2 then §4.3, timed: the adaptation's cost is part of the render.
void PmcIpIntegrator::adapt(IteratedAllocation::Plan* plan) {
    const Clock::time_point start = Clock::now();
    pixelIntegrator_->commitPixelRecords();  // §6.1: PMC-HI starts from the α so far
    std::vector<double> luminance;
    record_->varianceImage(&variance_, &luminance);
    alpha_ = mixtureWeights(variance_, luminance, settings_.epsilon, kDefaultCdPerUnit);
    const uint32_t spp =
        iterationsDone_ == maxIterations_ ? lastIterationSpp_ : settings_.iterationSpp;
    const uint64_t total = uint64_t(alpha_.size()) * spp;
    drawCounts(total, plan);
    std::vector<double> density(alpha_.size());
    for (size_t k = 0; k < alpha_.size(); ++k) {
        density[k] = double(total) * alpha_[k];
        // A pixel's count must stay exact in the film and the sampler.
        if (uint64_t(record_->count(k)) + plan->counts[k] > kMaxSpp)
            throw std::runtime_error("pmc_ip: pixel " + std::to_string(k) +
                                     " would get more than 2^24 samples");
    }
    if (settings_.image == ImageEstimate::Iterations) control_ = record_->pooledImage().values;
    record_->beginIteration(plan->counts, std::move(density), /*pilot=*/false);
    adaptSeconds_ += secondsSince(start);
}

bool PmcIpIntegrator::allocateKnownVariance(int iteration, IteratedAllocation::Plan* plan) {
    const size_t pixels = record_->pixels();
    if (iteration == 0) {  // the pilot
        plan->counts.assign(pixels, settings_.knownVarianceSpp);
        plan->pilot = true;
        pilot_ = true;
        record_->beginIteration(plan->counts,
                                std::vector<double>(pixels, settings_.knownVarianceSpp),
                                /*pilot=*/true);
        return true;
    }
    if (iteration > 1) return false;
    const Clock::time_point start = Clock::now();
    pilot_ = false;
    std::vector<double> luminance;
    record_->varianceImage(&variance_, &luminance);
    record_->clearVarianceSums();
    const uint64_t total = uint64_t(pixels) * spp_;
    std::vector<double> expected = staticAllocation(variance_, luminance, total, kDefaultCdPerUnit);
    // One sample each, then the rest by deterministic mixture sampling over n − 1, so that no
    // pixel goes without.
    double above = 0;
    for (double e : expected)
        above += e - 1;
    for (size_t k = 0; k < pixels; ++k)
        alpha_[k] = above > 0 ? (expected[k] - 1) / above : 1.0 / double(pixels);
    drawCounts(total - pixels, plan);
    for (size_t k = 0; k < pixels; ++k) {
        plan->counts[k] += 1;
        alpha_[k] = expected[k] / double(total);  // the channel: the allocation's share
        // Kept samples must stay below the pilot's indices (from kMaxSpp on).
        if (plan->counts[k] > kMaxSpp)
            throw std::runtime_error("pmc_ip: pixel " + std::to_string(k) +
                                     " would get more than 2^24 samples");
    }
    record_->beginIteration(plan->counts, std::move(expected), /*pilot=*/false);
    adaptSeconds_ += secondsSince(start);
    return true;
}

void PmcIpIntegrator::observe(const PixelVisit& visit, const std::vector<Rgb>& values,
                              const std::vector<Vec2>& offsets) {
    ran_.store(true, std::memory_order_relaxed);
    record_->record(size_t(visit.y) * width_ + visit.x, values, offsets);
}

void PmcIpIntegrator::completeIteration() {
    if (!currentIterationRan() || pilot_) {
        planned_ = false;
        return;
    }
    if (settings_.image == ImageEstimate::Iterations) {
        const std::vector<Rgb> e = record_->iterationEstimate(record_->iterations() - 1, control_);
        for (size_t k = 0; k < e.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                estimates_[k].sum[c] += e[k][c];
                estimates_[k].squares[c] += double(e[k][c]) * e[k][c];
            }
    }
    ++iterationsDone_;
    planned_ = false;
}

void PmcIpIntegrator::finish() {
    const Clock::time_point start = Clock::now();
    completeIteration();
    image_ = pixelEstimates();
    adaptSeconds_ += secondsSince(start);
}

PixelEstimates PmcIpIntegrator::iterationsImage() const {
    // The last iteration may have run without being added up (a render that ended without
    // asking the schedule again).
    const bool current = currentIterationRan() && !pilot_;
    const int t = iterationsDone_ + (current ? 1 : 0);
    std::vector<Rgb> last;
    if (current) last = record_->iterationEstimate(record_->iterations() - 1, control_);
    PixelEstimates out;
    out.values.resize(estimates_.size());
    out.variances.resize(estimates_.size());
    for (size_t k = 0; k < estimates_.size(); ++k) {
        float mean[3], variance[3];
        for (int c = 0; c < 3; ++c) {
            const double e = current ? last[k][c] : 0.0;
            const double sum = estimates_[k].sum[c] + e;
            const double squares = estimates_[k].squares[c] + e * e;
            const double m = sum / t;
            mean[c] = static_cast<float>(m);
            // The spread of the iterations' estimates.
            variance[c] =
                static_cast<float>(std::max(0.0, squares - t * m * m) / double(t - 1) / double(t));
        }
        out.values[k] = Rgb(mean[0], mean[1], mean[2]);
        out.variances[k] = Rgb(variance[0], variance[1], variance[2]);
    }
    return out;
}

PixelEstimates PmcIpIntegrator::pixelEstimates() const {
    if (!image_.values.empty()) return image_;
    if (!record_) return {};
    // A render cancelled between planning an iteration and running it leaves that iteration
    // in the record without samples: it is not part of the image.
    const bool unrun = planned_ && !pilot_ && !ran_.load(std::memory_order_relaxed);
    const size_t recorded = record_->iterations() - (unrun ? 1 : 0);
    if (recorded == 0) return {};
    const int completed = iterationsDone_ + (currentIterationRan() && !pilot_ ? 1 : 0);
    // One iteration (the initial image, or a static allocation) is its samples pooled.
    if (settings_.image == ImageEstimate::Pooled || completed <= 1)
        return record_->pooledImage(recorded);
    return iterationsImage();
}

std::vector<AuxiliaryChannel> PmcIpIntegrator::auxiliaryChannels() const {
    std::vector<AuxiliaryChannel> channels = pixelIntegrator_->auxiliaryChannels();
    AuxiliaryChannel alpha{"pmc.alpha",
                           "|P| alpha of the last iteration (1: a uniform share of its samples)",
                           std::vector<float>(alpha_.size())};
    AuxiliaryChannel variance{"pmc.variance",
                              "per-sample luminance variance the last alpha came from, over the "
                              "samples within each pixel's filter support",
                              std::vector<float>(variance_.size())};
    for (size_t k = 0; k < alpha_.size(); ++k) {
        alpha.values[k] = static_cast<float>(alpha_[k] * double(alpha_.size()));
        variance.values[k] = static_cast<float>(variance_[k]);
    }
    channels.push_back(std::move(alpha));
    channels.push_back(std::move(variance));
    return channels;
}

}  // namespace rr::pmc
