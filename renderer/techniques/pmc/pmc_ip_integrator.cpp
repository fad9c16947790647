#include "techniques/pmc/pmc_ip_integrator.h"

#include <chrono>
#include <stdexcept>

#include "config/config_error.h"
#include "math/tvi.h"
#include "render/iterated_allocation.h"
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

}  // namespace

PmcIpIntegrator::PmcIpIntegrator(std::unique_ptr<SampleIntegrator> pixelIntegrator,
                                 const PmcIpSettings& settings)
    : pixelIntegrator_(std::move(pixelIntegrator)), settings_(settings) {
    if (settings_.initialSpp < 2 || settings_.iterationSpp < 1)
        throw std::logic_error("pmc_ip needs two initial samples per pixel and iterations of one");
}

nlohmann::json PmcIpIntegrator::parameters() const {
    nlohmann::json p;
    p["type"] = name();
    p["integrator"] = pixelIntegrator_->parameters();
    p["initial_spp"] = settings_.initialSpp;
    p["iteration_spp"] = settings_.iterationSpp;
    p["epsilon"] = settings_.epsilon;
    p["image"] = settings_.image == ImageEstimate::Iterations ? "iterations" : "pooled";
    if (completedIterations() > 0) {
        p["iterations"] = completedIterations();
        p["adapt_seconds"] = adaptSeconds_;
    }
    return p;
}

std::unique_ptr<RenderSchedule> PmcIpIntegrator::schedule(const ScheduleInputs& in) {
    pixelIntegrator_->beginImage(in.width, in.height, /*iterated=*/true);
    const uint32_t initial = settings_.initialSpp, step = settings_.iterationSpp;
    if (in.spp < initial)
        throw ConfigError("/render/spp", "pmc_ip renders " + std::to_string(initial) +
                                             " initial samples per pixel; " +
                                             std::to_string(in.spp) + " spp is fewer");
    const uint64_t pixels = uint64_t(in.width) * uint64_t(in.height);
    width_ = in.width;
    seed_ = in.seed;
    // Iterations of `step` samples per pixel, the last taking what is left of the spp.
    maxIterations_ = int((in.spp - initial + step - 1) / step);
    lastIterationSpp_ = in.spp - initial - (maxIterations_ - 1) * step;
    iterationsDone_ = 0;
    planned_ = false;
    ran_ = false;
    adaptSeconds_ = 0;
    pixels_.assign(pixels, PixelState{});
    alpha_.assign(pixels, 1.0 / double(pixels));
    sampleWeight_.assign(pixels, 1.0 / initial);
    variance_.assign(pixels, 0.0);
    return std::make_unique<IteratedAllocation>(
        in.scene, *pixelIntegrator_, in.width, in.height, in.timeLimit,
        [this](const Film&, int iteration, std::vector<uint32_t>* counts) {
            return allocate(iteration, counts);
        },
        [this](const PixelVisit& visit, const std::vector<Rgb>& values) {
            observe(visit, values);
        });
}

bool PmcIpIntegrator::allocate(int iteration, std::vector<uint32_t>* counts) {
    completeIteration();
    if (iteration > maxIterations_) return false;
    if (iteration == 0)
        counts->assign(pixels_.size(), settings_.initialSpp);
    else
        adapt(counts);
    planned_ = true;
    ran_ = false;
    return true;
}

// §4.2 then §4.3, timed: the adaptation's cost is part of the render.
void PmcIpIntegrator::adapt(std::vector<uint32_t>* counts) {
    const auto start = std::chrono::steady_clock::now();
    pixelIntegrator_->commitPixelRecords();  // §6.1: PMC-HI starts from the α so far
    const size_t pixels = pixels_.size();
    std::vector<double> luminance(pixels);
    for (size_t k = 0; k < pixels; ++k) {
        const PixelState& p = pixels_[k];
        const double n = p.samples, mean = p.luminanceSum / n;
        luminance[k] = mean;
        variance_[k] = std::max(0.0, (p.luminanceSquares - n * mean * mean) / (n - 1));
    }
    alpha_ = mixtureWeights(variance_, luminance, settings_.epsilon, kDefaultCdPerUnit);
    const uint32_t spp =
        iterationsDone_ == maxIterations_ ? lastIterationSpp_ : settings_.iterationSpp;
    const uint64_t total = uint64_t(pixels) * spp;
    counts->resize(pixels);
    mixtureCounts(alpha_, total, residualOffset(seed_, iterationsDone_), *counts);
    for (size_t k = 0; k < pixels; ++k) {
        sampleWeight_[k] = 1.0 / (double(total) * alpha_[k]);
        PixelState& p = pixels_[k];
        // A pixel's count must stay exact in the film and the sampler.
        if (uint64_t(p.samples) + (*counts)[k] > kMaxSpp)
            throw std::runtime_error("pmc_ip: pixel " + std::to_string(k) +
                                     " would get more than 2^24 samples");
        for (int c = 0; c < 3; ++c)
            p.control[c] = p.rgbSum[c] / p.samples;
    }
    adaptSeconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void PmcIpIntegrator::observe(const PixelVisit& visit, const std::vector<Rgb>& values) {
    ran_.store(true, std::memory_order_relaxed);
    const size_t k = size_t(visit.y) * width_ + visit.x;
    PixelState& p = pixels_[k];
    double sum[3] = {0, 0, 0};
    for (const Rgb& v : values) {
        const double y = v.luminance();
        p.luminanceSum += y;
        p.luminanceSquares += y * y;
        for (int c = 0; c < 3; ++c)
            sum[c] += v[c];
    }
    const double n = double(values.size());
    for (int c = 0; c < 3; ++c) {
        p.iterationSum[c] += (sum[c] - n * p.control[c]) * sampleWeight_[k];
        p.rgbSum[c] += sum[c];
    }
    p.samples += uint32_t(values.size());
}

void PmcIpIntegrator::completeIteration() {
    if (!currentIterationRan()) {
        planned_ = false;
        return;
    }
    for (PixelState& p : pixels_)
        for (int c = 0; c < 3; ++c) {
            const double estimate = p.control[c] + p.iterationSum[c];
            p.estimateSum[c] += estimate;
            p.estimateSquares[c] += estimate * estimate;
            p.iterationSum[c] = 0;
        }
    ++iterationsDone_;
    planned_ = false;
}

PixelEstimates PmcIpIntegrator::pixelEstimates() const {
    const int t = completedIterations();
    // One iteration (the initial image) is the film's mean.
    if (settings_.image == ImageEstimate::Pooled || t <= 1) return {};
    const bool current = currentIterationRan();  // not yet added up: the render just ended
    PixelEstimates out;
    out.values.resize(pixels_.size());
    out.variances.resize(pixels_.size());
    for (size_t k = 0; k < pixels_.size(); ++k) {
        const PixelState& p = pixels_[k];
        float mean[3], variance[3];
        for (int c = 0; c < 3; ++c) {
            const double e = current ? p.control[c] + p.iterationSum[c] : 0.0;
            const double sum = p.estimateSum[c] + e, squares = p.estimateSquares[c] + e * e;
            const double m = sum / t;
            mean[c] = static_cast<float>(m);
            // The spread of the iterations' estimates; one iteration, the samples' own.
            variance[c] = static_cast<float>(
                t > 1 ? std::max(0.0, squares - t * m * m) / double(t - 1) / double(t) : 0.0);
        }
        out.values[k] = Rgb(mean[0], mean[1], mean[2]);
        out.variances[k] = Rgb(variance[0], variance[1], variance[2]);
    }
    return out;
}

std::vector<AuxiliaryChannel> PmcIpIntegrator::auxiliaryChannels() const {
    std::vector<AuxiliaryChannel> channels = pixelIntegrator_->auxiliaryChannels();
    AuxiliaryChannel alpha{"pmc.alpha",
                           "|P| alpha of the last iteration (1: a uniform share of its samples)",
                           std::vector<float>(alpha_.size())};
    AuxiliaryChannel variance{"pmc.variance",
                              "per-sample luminance variance the last alpha came from",
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
