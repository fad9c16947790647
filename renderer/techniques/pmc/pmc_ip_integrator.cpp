#include "techniques/pmc/pmc_ip_integrator.h"

#include <chrono>

#include "config/config_error.h"
#include "metrics/tvi.h"
#include "render/iterated_allocation.h"
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
    : pixelIntegrator_(std::move(pixelIntegrator)), settings_(settings) {}

nlohmann::json PmcIpIntegrator::parameters() const {
    nlohmann::json p;
    p["type"] = name();
    p["integrator"] = pixelIntegrator_->parameters();
    p["initial_spp"] = settings_.initialSpp;
    p["iteration_spp"] = settings_.iterationSpp;
    p["epsilon"] = settings_.epsilon;
    p["image"] = settings_.image == ImageEstimate::Iterations ? "iterations" : "pooled";
    if (iterationsDone_ > 0) {
        p["iterations"] = iterationsDone_;
        p["adapt_seconds"] = adaptSeconds_;
    }
    return p;
}

std::unique_ptr<RenderSchedule> PmcIpIntegrator::schedule(const ScheduleInputs& in) {
    const uint32_t initial = settings_.initialSpp, step = settings_.iterationSpp;
    if (in.spp < initial || (in.timeLimit == 0 && (in.spp - initial) % step != 0))
        throw ConfigError("/render/spp", "pmc_ip renders " + std::to_string(initial) +
                                             " initial samples per pixel and then iterations of " +
                                             std::to_string(step) + "; " + std::to_string(in.spp) +
                                             " spp is not " + std::to_string(initial) +
                                             " + a multiple of " + std::to_string(step));
    width_ = in.width;
    seed_ = in.seed;
    maxIterations_ = int((in.spp - initial) / step);
    iterationsDone_ = 0;
    adaptSeconds_ = 0;
    const size_t pixels = size_t(in.width) * in.height;
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
    if (iteration > maxIterations_) return false;
    if (iteration == 0)
        counts->assign(pixels_.size(), settings_.initialSpp);
    else
        adapt(counts);
    ++iterationsDone_;
    return true;
}

// §4.2 then §4.3, timed: the adaptation's cost is part of the render.
void PmcIpIntegrator::adapt(std::vector<uint32_t>* counts) {
    const auto start = std::chrono::steady_clock::now();
    const size_t pixels = pixels_.size();
    std::vector<double> luminance(pixels);
    for (size_t k = 0; k < pixels; ++k) {
        const PixelState& p = pixels_[k];
        const double n = p.samples, mean = p.luminanceSum / n;
        luminance[k] = mean;
        variance_[k] = std::max(0.0, (p.luminanceSquares - n * mean * mean) / (n - 1));
    }
    alpha_ = mixtureWeights(variance_, luminance, settings_.epsilon, kDefaultCdPerUnit);
    const uint64_t total = uint64_t(pixels) * settings_.iterationSpp;
    mixtureCounts(alpha_, total, residualOffset(seed_, iterationsDone_), counts);
    for (size_t k = 0; k < pixels; ++k) {
        sampleWeight_[k] = 1.0 / (double(total) * alpha_[k]);
        // The control variate of this iteration's estimate: the pixel's mean so far.
        PixelState& p = pixels_[k];
        for (int c = 0; c < 3; ++c)
            p.estimateSum[c] += p.rgbSum[c] / p.samples;
    }
    adaptSeconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void PmcIpIntegrator::observe(const PixelVisit& visit, const std::vector<Rgb>& values) {
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
    // The iteration's estimate is c + Σ (L − c) / (N α), c added by adapt() (pixels without
    // samples in the iteration included).
    const double n = double(values.size());
    for (int c = 0; c < 3; ++c) {
        const double before = p.samples > 0 ? p.rgbSum[c] / p.samples : 0.0;
        p.estimateSum[c] += (sum[c] - n * before) * sampleWeight_[k];
        p.rgbSum[c] += sum[c];
    }
    p.samples += uint32_t(values.size());
}

std::vector<Rgb> PmcIpIntegrator::pixelEstimates() const {
    if (settings_.image == ImageEstimate::Pooled || iterationsDone_ == 0) return {};
    std::vector<Rgb> image(pixels_.size());
    for (size_t k = 0; k < pixels_.size(); ++k) {
        const double* sum = pixels_[k].estimateSum;
        image[k] = Rgb(static_cast<float>(sum[0] / iterationsDone_),
                       static_cast<float>(sum[1] / iterationsDone_),
                       static_cast<float>(sum[2] / iterationsDone_));
    }
    return image;
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
