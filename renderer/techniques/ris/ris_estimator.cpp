#include "techniques/ris/ris_estimator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "config/config_error.h"
#include "sampling/warps.h"
#include "scene/scene.h"
#include "techniques/ris/reservoir.h"
#include "techniques/ris/ris_decisions.h"

namespace rr::ris {

namespace {

using Clock = std::chrono::steady_clock;

double secondsBetween(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double>(b - a).count();
}

// What reading the clock adds to a timed block: the median gap between consecutive reads,
// measured once. The pilot's blocks are short (a few candidates, a couple of shadow rays), so
// it is subtracted from each.
double clockReadSeconds() {
    static const double seconds = [] {
        std::array<double, 255> gaps;
        for (double& gap : gaps) {
            const Clock::time_point a = Clock::now();
            gap = secondsBetween(a, Clock::now());
        }
        std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
        return gaps[gaps.size() / 2];
    }();
    return seconds;
}

// The time of a block that ran from `a` to `b`, less the clock read.
double blockSeconds(Clock::time_point a, Clock::time_point b) {
    return std::max(0.0, secondsBetween(a, b) - clockReadSeconds());
}

uint32_t ceilCount(double x) {
    return static_cast<uint32_t>(std::ceil(x));
}

// An integer count as it is; a fractional one rounded randomly by draw `repeat` of the
// vertex's resample_count decision (0: M, 1: N).
uint32_t countAt(const ShadingPoint& point, double x, uint32_t repeat) {
    if (x == std::floor(x)) return static_cast<uint32_t>(x);
    return roundRandomly(x, point.decide1D(kResampleCount, repeat, 2));
}

// The pilot's work per shading point and round: as many candidates as samples, each finished,
// as the render does at M = 1 with this many light samples at a point. Its candidates come as
// one batch (CandidateStream), as the render draws them, and its shadow rays are as many from
// one point as the render's (a few dozen nanoseconds cheaper each than the first from a point:
// rays from one point share the acceleration structure's top). Blocks of a few draws also let
// the clock's own cost, subtracted, dominate: measured with two samples of 8 candidates a round,
// T_Y came out 25 % higher than with 8 samples of 2 (fig. 4 with the map; issue 40).
constexpr uint32_t kProbeSamples = 16;
// Rounds per shading point: the first warms up what the point's later draws reuse (its material,
// a polygon's view from it), untimed; the others time candidates and finishing in turn, so
// that both stages see the same cache state (steady-state costs; issue 40).
constexpr uint32_t kProbeRounds = 2;

}  // namespace

const char* sourceName(CandidateSource source) {
    switch (source) {
        case CandidateSource::Light:
            return "light";
        case CandidateSource::LightProxy:
            return "light_proxy";
        case CandidateSource::UniformHemisphere:
            return "uniform_hemisphere";
        case CandidateSource::CosineHemisphere:
            return "cosine_hemisphere";
        case CandidateSource::Bsdf:
            return "bsdf";
        case CandidateSource::Mixture:
            return "mixture";
    }
    return "?";
}

CostTally& CostTally::operator+=(const CostTally& o) {
    candidateSeconds += o.candidateSeconds;
    finishSeconds += o.finishSeconds;
    candidates += o.candidates;
    finishes += o.finishes;
    return *this;
}

CandidateCosts CostTally::costs() const {
    return {candidates ? candidateSeconds / double(candidates) : 0,
            finishes ? finishSeconds / double(finishes) : 0};
}

RisEstimator::RisEstimator(CandidateSource source, CandidateCounts counts,
                           CandidateCounts maxCounts)
    : source_(source), counts_(counts), maxCounts_(maxCounts) {}

nlohmann::json RisEstimator::parameters() const {
    nlohmann::json p = readParameters();
    p["source"] = sourceName(source_);
    p["candidates"] = counts_.m;
    p["samples"] = counts_.n;
    return p;
}

void RisEstimator::prepare(const Scene& scene, const std::string& pointer) {
    if (source_ == CandidateSource::LightProxy) standIns_ = LightStandIns(scene.lights());
    if (source_ != CandidateSource::Mixture) return;
    for (const Light* light : scene.lights())
        if (!light->isInfinite())
            throw ConfigError(pointer + "/source",
                              "source \"mixture\" needs the light-sampling density of BSDF "
                              "directions, which it has for infinite lights only: light " +
                                  std::to_string(light->index()) + " is not infinite");
}

uint32_t RisEstimator::lightSamples() const {
    return ceilCount(maxCounts_.n);
}

uint32_t RisEstimator::decisionRepeats() const {
    return ceilCount(maxCounts_.n) * ceilCount(maxCounts_.m);
}

bool RisEstimator::candidateFrom(const ShadingPoint& point, const LightDraw& draw,
                                 Candidate* c) const {
    if (!draw.drawn) return false;
    c->light = draw.sample;
    c->pdf = draw.pdf;
    c->emitter = draw.light;
    c->direction = c->light.direction;
    c->scattering = point.scattering(c->direction);
    c->target = (c->scattering * c->light.radiance).luminance();
    return true;
}

bool RisEstimator::CandidateStream::next(Candidate* c) {
    const uint32_t k = position_++;
    if (!estimator_.fromLights()) return estimator_.drawCandidate(point_, repeatAt(k), repeats_, c);
    if (used_ == buffered_) {
        std::array<uint32_t, kBatch> repeats;
        buffered_ = std::min(kBatch, total_ - k);
        for (uint32_t t = 0; t < buffered_; ++t)
            repeats[t] = repeatAt(k + t);
        point_.sampleLights(std::span(repeats.data(), buffered_), repeats_, estimator_.standIns(),
                            batch_.data());
        used_ = 0;
    }
    return estimator_.candidateFrom(point_, batch_[used_++], c);
}

bool RisEstimator::drawCandidate(ShadingPoint& point, uint32_t repeat, uint32_t repeats,
                                 Candidate* c) const {
    if (fromLights()) {
        LightDraw draw;
        point.sampleLights(std::span(&repeat, 1), repeats, standIns(), &draw);
        return candidateFrom(point, draw, c);
    }
    if (source_ == CandidateSource::Mixture) return drawFromMixture(point, repeat, repeats, c);
    const Vec2 u = point.decide2D(kCandidateDirection, repeat, repeats);
    const Frame* frame = point.frame();
    if (source_ == CandidateSource::Bsdf) {
        const float uLobe = point.decide1D(kCandidateLobe, repeat, repeats);
        if (!point.sampleScattering(uLobe, u, &c->direction, &c->pdf)) return false;
    } else if (!frame) {  // a point in a medium: the whole sphere
        c->direction = squareToUniformSphere(u);
        c->pdf = uniformSpherePdf();
    } else {
        const bool uniform = source_ == CandidateSource::UniformHemisphere;
        const Vec3 local = uniform ? squareToUniformHemisphere(u) : squareToCosineHemisphere(u);
        c->pdf = uniform ? uniformHemispherePdf(local) : cosineHemispherePdf(local);
        if (!(c->pdf > 0)) return false;
        c->direction = frame->toWorld(local);
    }
    c->scattering = point.scattering(c->direction);
    c->target = c->scattering.luminance();
    return true;
}

bool RisEstimator::drawFromMixture(ShadingPoint& point, uint32_t repeat, uint32_t repeats,
                                   Candidate* c) const {
    // The lower half of the coordinate picks light sampling, the upper half the BSDF, and
    // rescaled it is the BSDF's lobe coordinate.
    const float u = point.decide1D(kCandidateLobe, repeat, repeats);
    // Each draw's own density is not needed: the mixture's is evaluated below.
    float drawPdf;
    if (u < 0.5f) {
        LightSample ls;
        const Light* drawnLight;
        if (!point.sampleLight(repeat, repeats, /*standIns=*/nullptr, &ls, &drawPdf, &drawnLight))
            return false;
        c->direction = ls.direction;
    } else {
        const Vec2 uDirection = point.decide2D(kCandidateDirection, repeat, repeats);
        if (!point.sampleScattering(2 * u - 1, uDirection, &c->direction, &drawPdf)) return false;
    }
    // The mixture's density counts both ways of drawing the direction, each by the density of
    // the sampler that drew it (sampleScatteringPdf: not a guide's scatteringPdf).
    Rgb le;
    const float lightPdf = point.infiniteLightPdf(c->direction, &le);
    c->pdf = 0.5f * (lightPdf + point.sampleScatteringPdf(c->direction));
    if (!(c->pdf > 0)) return false;
    c->scattering = point.scattering(c->direction);
    c->target = (c->scattering * le).luminance();
    return true;
}

Rgb RisEstimator::finish(ShadingPoint& point, const Candidate& c, float density) const {
    if (fromLights()) {
        float survival;
        const Rgb tr = point.visibility(c.light, c.emitter->isInfinite(), &survival);
        if (tr.isBlack()) return Rgb(0.0f);
        const LightStandIn* standIn =
            source_ == CandidateSource::LightProxy ? standIns_.of(*c.emitter) : nullptr;
        const Rgb le = standIn ? standIn->exactRadiance(c.light) : c.light.radiance;
        return point.contribution(c.scattering, le, tr, 1.0f, density);
    }
    const Rgb le = point.incidentEmission(c.direction);
    if (le.isBlack()) return Rgb(0.0f);
    return point.contribution(c.scattering, le, Rgb(1.0f), 1.0f, density);
}

void RisEstimator::estimate(ShadingPoint& point, const CandidateCounts& counts) const {
    const uint32_t mMax = ceilCount(counts.m), nMax = ceilCount(counts.n);
    const uint32_t repeats = mMax * nMax;
    const uint32_t m = countAt(point, counts.m, 0), n = countAt(point, counts.n, 1);
    CandidateStream stream(*this, point, n, m, mMax, 0, repeats);
    for (uint32_t i = 0; i < n; ++i) {
        auto draw = [&](uint32_t, Candidate* c) { return stream.next(c); };
        auto select = [&](uint32_t j) {
            return point.decide1D(kResampleSelect, i * mMax + j, repeats);
        };
        Candidate y;
        float density;
        if (!resample(m, draw, select, &y, &density)) continue;
        // Eq. (1)'s 1/N joins the density.
        const Rgb contribution = finish(point, y, density * static_cast<float>(n));
        if (!contribution.isBlack()) point.add(contribution);
    }
}

void RisEstimator::measureCosts(ShadingPoint& point, bool timed, CostTally* tally) const {
    constexpr uint32_t repeats = kProbeRounds * kProbeSamples;
    for (uint32_t round = 0; round < kProbeRounds; ++round) {
        std::array<Candidate, kProbeSamples> candidates;
        std::array<bool, kProbeSamples> drawn;
        CandidateStream stream(*this, point, kProbeSamples, 1, 1, round * kProbeSamples, repeats);
        const Clock::time_point start = Clock::now();
        for (uint32_t i = 0; i < kProbeSamples; ++i)
            drawn[i] = stream.next(&candidates[i]) && candidates[i].target > 0;
        const Clock::time_point sampled = Clock::now();
        uint32_t finished = 0;
        for (uint32_t i = 0; i < kProbeSamples; ++i) {
            if (!drawn[i]) continue;
            finish(point, candidates[i], candidates[i].pdf);
            ++finished;
        }
        const Clock::time_point end = Clock::now();
        if (round == 0 || !timed) continue;
        tally->candidateSeconds += blockSeconds(start, sampled);
        tally->candidates += kProbeSamples;
        if (finished == 0) continue;
        tally->finishSeconds += blockSeconds(sampled, end);
        tally->finishes += finished;
    }
}

void RisEstimator::addVarianceTerms(ShadingPoint& point, uint32_t samples,
                                    VarianceTerms* terms) const {
    for (uint32_t k = 0; k < samples; ++k) {
        Candidate c;
        if (!drawCandidate(point, k, samples, &c)) {
            terms->add(Rgb(0.0f), 0, 1);  // no sample: the estimate is 0
            continue;
        }
        const Rgb f = c.target > 0 ? finish(point, c, 1.0f) : Rgb(0.0f);
        terms->add(f, c.target, c.pdf);
    }
}

}  // namespace rr::ris
