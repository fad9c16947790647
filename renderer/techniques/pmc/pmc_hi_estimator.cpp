#include "techniques/pmc/pmc_hi_estimator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "config/config_error.h"
#include "math/frame.h"
#include "sampling/warps.h"
#include "techniques/pmc/mixture_allocation.h"
#include "techniques/pmc/pmc_decisions.h"

namespace rr::pmc {

namespace {

constexpr uint32_t kMaxComponents = PmcHiEstimator::kMaxLights + 2;
constexpr uint32_t kBsdf = 0;  // then the lights, then the cone
constexpr float kConeSlack = 1e-3f;

float angleBetween(const Vec3& a, const Vec3& b) {
    return std::acos(std::clamp(dot(a, b), -1.0f, 1.0f));
}

}  // namespace

// The mixture's parameters at one iteration.
struct PmcHiEstimator::Kernel {
    std::array<double, kMaxComponents> alpha{};
    Vec3 coneAxis{0, 0, 1};
    float coneOneMinusCos = 0;  // 0: the cone is off

    bool coneEntered = false;  // the cone has had its share once

    float conePdf(const Vec3& w) const {
        if (coneOneMinusCos <= 0) return 0;
        // 1 − cos θ as sin²θ/(1 + cos θ), accurate in narrow cones (1 − dot(w, d) in float
        // put 6 % of a 10⁻³-radian cone's own draws outside it, dropping their density); the
        // slack covers the rounding of the draws' world directions.
        const float c = dot(w, coneAxis);
        if (c <= 0) return 0;
        const Vec3 s = cross(w, coneAxis);
        if (dot(s, s) / (1 + c) > coneOneMinusCos * (1 + kConeSlack)) return 0;
        return uniformConePdf(coneOneMinusCos);
    }
};

// One member of the population: where it points, what it found, and its weight.
struct PmcHiEstimator::Draw {
    uint32_t component = 0;
    bool found = false;  // a direction with some f·Le
    Vec3 direction;
    Rgb f, le, tr;
    int areaLight = -1;  // the area light the sample lies on
    float areaLightPdf = 0;
    // One for all lights: the light's selection × areaLightPdf, or for a direction that escapes
    // the summed density of the infinite lights (ShadingPoint::infiniteLightPdf).
    float selectedLightPdf = 0;
    bool escaped = false;  // a direction to the infinite lights
    float weight = 0;      // luminance of f·Le·V / K, for the adaptation
};

nlohmann::json PmcHiEstimator::parameters() const {
    nlohmann::json p = readParameters();
    p["light_components"] = oneForAllLights_ ? "one" : "each";  // as resolved for the scene
    return p;
}

PixelRecordLayout PmcHiEstimator::pixelRecords() const {
    if (!records()) return {};
    PixelRecordLayout layout{{"pmc_hi.alpha.bsdf"},
                             "PMC-HI's weight of this mixture component after the estimate's "
                             "iterations (alpha^(T), fig. 7), mean over the pixel's first hits",
                             settings_.feedback ? "feedback" : ""};
    if (oneForAllLights_)
        layout.names.push_back("pmc_hi.alpha.lights");
    else
        for (const Light* light : lights_)
            layout.names.push_back("pmc_hi.alpha.light" + std::to_string(light->index()));
    layout.names.push_back("pmc_hi.alpha.cone");
    return layout;
}

void PmcHiEstimator::prepare(const Scene& scene, const std::string& pointer) {
    lights_.assign(scene.lights().begin(), scene.lights().end());
    infiniteLights_.assign(scene.infiniteLights().begin(), scene.infiniteLights().end());
    for (const Light* light : lights_)
        if (light->isDelta())
            throw ConfigError(pointer, "pmc_hi mixes densities over directions, which light " +
                                           std::to_string(light->index()) +
                                           " (a point or spot light) does not have");
    const bool many = lights_.size() > kMaxLights;
    if (many && settings_.lightComponents == LightComponents::Each)
        throw ConfigError(pointer + "/light_components",
                          "pmc_hi gives each light a mixture component, up to " +
                              std::to_string(kMaxLights) + " lights; the scene has " +
                              std::to_string(lights_.size()) + " (\"one\" samples them all)");
    oneForAllLights_ = settings_.lightComponents == LightComponents::One ||
                       (many && settings_.lightComponents == LightComponents::Auto);
    if (settings_.floor * double(lightComponents() + 1) >= 1)
        throw ConfigError(pointer + "/floor", "the floors of the BSDF and the " +
                                                  std::to_string(lightComponents()) +
                                                  " light components must leave room for "
                                                  "adaptation (floor × (components − 1) < 1)");
}

// Draws a sample of `component` and finds its f, Le and visibility.
bool PmcHiEstimator::draw(ShadingPoint& point, const Kernel& kernel, uint32_t component,
                          uint32_t repeat, uint32_t repeats, Draw* d) const {
    *d = Draw{};
    d->component = component;
    if (component >= 1 && component <= lightComponents())
        return drawLightPoint(point, component, repeat, repeats, d);
    const Vec2 u = point.decide2D(kMixtureDirection, repeat, repeats);
    if (component == kBsdf) {
        float pdf;
        if (!point.sampleScattering(point.decide1D(kMixtureLobe, repeat, repeats), u, &d->direction,
                                    &pdf))
            return false;
    } else {
        d->direction =
            Frame(kernel.coneAxis).toWorld(squareToUniformCone(u, kernel.coneOneMinusCos));
    }
    d->f = point.scattering(d->direction);
    if (d->f.isBlack()) return false;
    d->le = findEmission(point, d);
    d->tr = Rgb(1.0f);
    d->found = !d->le.isBlack();
    return d->found;
}

// A light component's draw: a point on its light by the light's own sampler, or with one
// component for all lights a light and a point by the integrator's light sampling.
bool PmcHiEstimator::drawLightPoint(ShadingPoint& point, uint32_t component, uint32_t repeat,
                                    uint32_t repeats, Draw* d) const {
    LightSample ls;
    const Light* light = nullptr;
    if (oneForAllLights_) {
        float pdf;
        if (!point.sampleLight(repeat, repeats, /*standIns=*/nullptr, &ls, &pdf, &light) ||
            !(pdf > 0))
            return false;
        d->selectedLightPdf = pdf;
    } else {
        light = lights_[component - 1];
        const Vec2 u = point.decide2D(kMixtureDirection, repeat, repeats);
        if (!point.sampleLightOf(*light, u, &ls) || !(ls.pdf > 0)) return false;
    }
    d->direction = ls.direction;
    d->f = point.scattering(ls.direction);
    if (light->isInfinite()) {
        d->escaped = true;
        if (oneForAllLights_)  // every infinite light's radiance and density, in one pass
            d->selectedLightPdf = point.infiniteLightPdf(ls.direction, &d->le);
        else
            for (const Light* other : infiniteLights_)
                d->le += other->escapedRadiance(ls.direction);
    } else {
        d->areaLight = light->index();
        d->areaLightPdf = ls.pdf;
        d->le = ls.radiance;
    }
    if (d->f.isBlack() || d->le.isBlack()) return false;
    float survival;
    d->tr = point.visibility(ls, light->isInfinite(), &survival);
    d->found = !d->tr.isBlack();
    return d->found;
}

// The emission along d->direction, and where it comes from (the light and the densities
// density() needs).
Rgb PmcHiEstimator::findEmission(ShadingPoint& point, Draw* d) const {
    EmissionSource source{.withSelection = oneForAllLights_};
    const Rgb le = point.incidentEmission(d->direction, &source);
    d->escaped = source.escaped;
    d->selectedLightPdf = source.selectedLightPdf;
    if (source.areaLight) {
        d->areaLight = source.areaLight->index();
        d->areaLightPdf = source.areaLightPdf;
    }
    return le;
}

// Eq. (8)'s denominator: every component's density of the sample.
float PmcHiEstimator::density(const ShadingPoint& point, const Kernel& kernel,
                              const Draw& d) const {
    double k = kernel.alpha[kBsdf] * point.sampleScatteringPdf(d.direction);
    const uint32_t cone = components() - 1;
    if (kernel.alpha[cone] > 0) k += kernel.alpha[cone] * kernel.conePdf(d.direction);
    if (oneForAllLights_) {
        // The integrator's light sampling: the selected light's density, or every infinite
        // light's for a direction that escapes (both found with the draw).
        if (d.areaLight >= 0 || d.escaped) k += kernel.alpha[1] * d.selectedLightPdf;
        return static_cast<float>(k);
    }
    if (d.areaLight >= 0) k += kernel.alpha[1 + d.areaLight] * d.areaLightPdf;
    if (d.escaped)
        for (const Light* light : infiniteLights_)
            k += kernel.alpha[1 + light->index()] * point.lightDirectionPdf(*light, d.direction);
    return static_cast<float>(k);
}

// Eq. (9) and the cone's axis and spread from the population just drawn.
void PmcHiEstimator::adapt(const Kernel& previous, const Draw* draws, uint32_t count,
                           Kernel* next) const {
    *next = previous;
    const uint32_t m = components(), cone = m - 1;
    std::array<double, kMaxComponents> sums{};
    double total = 0;
    Vec3 mean(0.0f);
    for (uint32_t i = 0; i < count; ++i) {
        sums[draws[i].component] += draws[i].weight;
        total += draws[i].weight;
        mean += draws[i].direction * draws[i].weight;
    }
    if (!(total > 0)) return;  // nothing found: keep the kernel
    for (uint32_t k = 0; k < m; ++k)
        next->alpha[k] = sums[k] / total;
    // The cone about the weighted mean direction, its half-angle the weighted RMS angle.
    const float meanLength = length(mean);
    if (meanLength > 0) {
        next->coneAxis = mean / meanLength;
        double spread = 0;
        for (uint32_t i = 0; i < count; ++i) {
            const double a = angleBetween(draws[i].direction, next->coneAxis);
            spread += draws[i].weight * a * a;
        }
        const float beta = std::clamp(float(std::sqrt(spread / total)), kMinConeAngle, 0.5f * kPi);
        next->coneOneMinusCos = 2 * std::sin(0.5f * beta) * std::sin(0.5f * beta);
    }
    // The cone enters with its share at the first adaptation that found something (after
    // iteration 0, unless that found nothing); the others make room.
    if (!previous.coneEntered && next->coneOneMinusCos > 0) {
        for (uint32_t k = 0; k < cone; ++k)
            next->alpha[k] *= 1 - settings_.coneShare;
        next->alpha[cone] = settings_.coneShare;
        next->coneEntered = true;
    }
    applyFloors(next);
}

// Floors for the BSDF and the lights, which between them cover the integrand.
void PmcHiEstimator::applyFloors(Kernel* kernel) const {
    const uint32_t m = components(), cone = m - 1;
    double sum = 0;
    for (uint32_t k = 0; k < m; ++k) {
        if (k != cone) kernel->alpha[k] = std::max(kernel->alpha[k], settings_.floor);
        sum += kernel->alpha[k];
    }
    for (uint32_t k = 0; k < m; ++k)
        kernel->alpha[k] /= sum;
}

// Iteration 0's kernel: equal α over the BSDF and the lights, or with feedback the pixel's
// committed α (§6.1); the cone off either way (its axis and angle are the point's own).
PmcHiEstimator::Kernel PmcHiEstimator::initialKernel(const ShadingPoint& point) const {
    const uint32_t m = components(), cone = m - 1;
    Kernel kernel;
    const float* start = settings_.feedback ? point.recordedStart() : nullptr;
    for (uint32_t k = 0; k < cone; ++k)
        kernel.alpha[k] = start ? double(start[k]) : 1.0 / double(m - 1);
    if (start) applyFloors(&kernel);
    return kernel;
}

// Draws iteration t's population of n from `kernel` into `draws` (deterministic mixture
// sampling for the counts) and calls found(draw, density) for each sample that found emission;
// returns how many were drawn.
template <class Found>
uint32_t PmcHiEstimator::drawIteration(ShadingPoint& point, const Kernel& kernel, uint32_t t,
                                       uint32_t n, uint32_t iterations, Draw* draws,
                                       Found&& found) const {
    const uint32_t m = components();
    std::array<uint32_t, kMaxComponents> counts{};
    mixtureCounts(std::span<const double>(kernel.alpha.data(), m), n,
                  point.decide1D(kMixtureCount, t, iterations),
                  std::span<uint32_t>(counts.data(), m));
    uint32_t i = 0;
    for (uint32_t k = 0; k < m; ++k)
        for (uint32_t c = 0; c < counts[k]; ++c, ++i) {
            Draw& d = draws[i];
            if (!draw(point, kernel, k, t * n + i, n * iterations, &d)) continue;
            const float density = this->density(point, kernel, d);
            if (density > 0) found(d, density);
        }
    return i;
}

void PmcHiEstimator::estimate(ShadingPoint& point) const {
    const uint32_t m = components(), n = populationSize();
    const uint32_t iterations = settings_.iterations;
    Kernel kernel = initialKernel(point);
    // One population per thread, reused: no allocation or clearing per shading point (each
    // draw resets its entry).
    thread_local std::vector<Draw> draws;
    if (draws.size() < n) draws.resize(n);
    const float sampleWeight = 1.0f / float(n * iterations);
    for (uint32_t t = 0; t < iterations; ++t) {
        const uint32_t drawn = drawIteration(
            point, kernel, t, n, iterations, draws.data(), [&](Draw& d, float density) {
                d.weight = (d.f * d.le * d.tr).luminance() / density;
                point.add(point.contribution(d.f, d.le, d.tr, sampleWeight, density));
            });
        // After the last iteration only for the records: α^(T), which no draw uses.
        if (t + 1 < iterations || records()) {
            const Kernel previous = kernel;
            adapt(previous, draws.data(), drawn, &kernel);
        }
    }
    if (records()) {
        std::array<float, kMaxComponents> alpha;
        for (uint32_t k = 0; k < m; ++k)
            alpha[k] = static_cast<float>(kernel.alpha[k]);
        point.record(std::span<const float>(alpha.data(), m));
    }
}

PmcHiEstimator::Kernel PmcHiEstimator::kernelOf(const MixtureParameters& p) const {
    if (p.alpha.size() != components())
        throw std::invalid_argument("pmc_hi: one α per mixture component");
    double sum = 0;
    for (double a : p.alpha)
        sum += a;
    if (std::abs(sum - 1) > 1e-9) throw std::invalid_argument("pmc_hi: α must sum to one");
    if (p.alpha.back() > 0 && !(p.coneAngle > 0))
        throw std::invalid_argument("pmc_hi: a cone with weight needs an angle");
    Kernel kernel;
    std::copy(p.alpha.begin(), p.alpha.end(), kernel.alpha.begin());
    kernel.coneAxis = normalize(p.coneAxis);
    kernel.coneOneMinusCos = 2 * std::sin(0.5f * p.coneAngle) * std::sin(0.5f * p.coneAngle);
    return kernel;
}

std::vector<PmcHiEstimator::MixtureSample> PmcHiEstimator::drawPopulation(
    ShadingPoint& point, const MixtureParameters& p, uint32_t n) const {
    const Kernel kernel = kernelOf(p);
    std::vector<Draw> draws(n);
    std::vector<MixtureSample> found;
    drawIteration(point, kernel, 0, n, 1, draws.data(), [&](const Draw& d, float density) {
        found.push_back({d.component, d.direction, density});
    });
    return found;
}

float PmcHiEstimator::mixtureDensity(ShadingPoint& point, const MixtureParameters& p,
                                     const Vec3& wi) const {
    Draw d;
    d.direction = wi;
    if (point.scattering(wi).isBlack() || findEmission(point, &d).isBlack()) return 0;
    return density(point, kernelOf(p), d);
}

}  // namespace rr::pmc
