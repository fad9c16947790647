// Resampled importance sampling of direct light (Talbot, Cline & Egbert 2005), a direct-lighting
// estimator (integrators/direct_lighting_estimator.h) usable by `direct`, at every vertex of
// `path_mis`, and by the `ris` integrator (ris_integrator.h), which also chooses M and N.
//
// Per shading point, N samples; each draws M fresh candidates X_j from the source p, keeps one,
// Y, with probability w_j / Σw where w_j = ĝ(X_j)/p(X_j) (a streaming reservoir: the
// candidates are never stored), and only then evaluates the rest of the integrand, V: the shadow
// ray. Eq. (1): Î = (1/N) Σ_i f(Y_i)/ĝ(Y_i) · (1/M) Σ_j w_ij.
//  - source `light` (§5.1): a candidate is a light and a point on it from the scene's light
//    sampling, p = P(light)·p(ω) per solid angle; ĝ = luminance(Fs·|cos θ|·Le), the unoccluded
//    integrand (G's other factors are in p's change of measure); f adds visibility.
//  - source `light_proxy`: the same, but candidates come from each light's cheaper stand-in
//    (scene/light_stand_in.h: an environment map draws blocks of texels and ĝ uses the block's
//    mean radiance); the chosen sample is finished with the light's exact radiance. p is still
//    exact, ĝ only approximates, which eq. (1) allows. A light without a stand-in gives its
//    own samples, as under `light`.
//  - sources `uniform_hemisphere`, `cosine_hemisphere` (about the shading normal) and `bsdf`
//    (§5.2): a candidate is a direction; ĝ = luminance(Fs·|cos θ|); f adds the emission a ray in
//    that direction finds. The hemispheres cover reflection only: transmissive materials need
//    `bsdf`. Surfaces in scenes without media only.
//  - source `mixture` (the two-stage paper's "RIS 2", Cline et al. 2006 §6): one-sample MIS's
//    density, p = ½·(light sampling's density + the BSDF's) per direction; one coordinate picks
//    the strategy of each candidate (structured samplers stratify it over the M candidates, so
//    M = 2 draws about one of each). ĝ = luminance(Fs·|cos θ|·Le) unoccluded; f adds the
//    emission a ray finds. Lights must all be infinite (a direction then names the light
//    point, so p can be evaluated at a BSDF candidate); surfaces without media only.
// Fractional M and N are rounded randomly per shading point (the resample_count decision), which
// keeps the estimate unbiased. With M = 1 the estimator is light sampling exactly: the same
// decisions and the same arithmetic as `light` with N light samples.
#pragma once

#include <array>
#include <cstdint>

#include "integrators/direct_lighting_estimator.h"
#include "techniques/ris/candidate_counts.h"

namespace rr::ris {

enum class CandidateSource : uint8_t {
    Light,
    LightProxy,
    UniformHemisphere,
    CosineHemisphere,
    Bsdf,
    Mixture
};

const char* sourceName(CandidateSource source);

// A candidate: its direction, what ĝ and p say of it, and what finishing it needs.
struct Candidate {
    Vec3 direction;
    LightSample light;  // light sources: the point on the light
    const Light* emitter = nullptr;
    Rgb scattering;    // Fs·|cos θ| at a surface, the phase function in a medium
    float pdf = 0;     // p, per solid angle
    float target = 0;  // ĝ
};

// What the pilot of §5.1 measured: the seconds spent drawing candidates and finishing chosen
// samples, and how many of each.
struct CostTally {
    double candidateSeconds = 0, finishSeconds = 0;
    uint64_t candidates = 0, finishes = 0;
    CostTally& operator+=(const CostTally& o);
    CandidateCosts costs() const;
};

class RisEstimator final : public DirectLightingEstimator {
  public:
    // `maxCounts`: the largest M and N the estimate will be asked for (sets the decisions'
    // repeat counts, which structured samplers stratify together).
    RisEstimator(CandidateSource source, CandidateCounts counts, CandidateCounts maxCounts);
    RisEstimator(CandidateSource source, CandidateCounts counts)
        : RisEstimator(source, counts, counts) {}

    std::string name() const override { return "ris"; }
    nlohmann::json parameters() const override;
    uint32_t lightSamples() const override;
    // The estimate covers every light a non-specular direction can find.
    FoundEmission foundEmission() const override { return FoundEmission::Excluded; }
    uint32_t decisionRepeats() const override;
    bool worksInMedia() const override { return fromLights(); }
    // `light_proxy` finds the lights' stand-ins; `mixture` refuses a scene with lights that are
    // not infinite.
    void prepare(const Scene& scene, const std::string& pointer) override;

    void estimate(ShadingPoint& point) const override { estimate(point, counts_); }
    // With counts of the caller's (per pixel, as the `ris` integrator's optimal M and N), each
    // at most the maximum counts.
    void estimate(ShadingPoint& point, const CandidateCounts& counts) const;

    // The pilot: times both stages at `point` (in rounds: a round's candidates, then each of
    // them finished, each stage timed as one block), after a round that warms up, untimed;
    // nothing timed unless `timed` (the pilot's own warm-up).
    void measureCosts(ShadingPoint& point, bool timed, CostTally* tally) const;
    // Adds `samples` candidates X ~ p, each finished (f with its shadow ray), to eq. (2)'s terms.
    void addVarianceTerms(ShadingPoint& point, uint32_t samples, VarianceTerms* terms) const;

    CandidateSource source() const { return source_; }
    const CandidateCounts& counts() const { return counts_; }
    // Directions from a hemisphere or the BSDF find emitters only by hitting them; the mixture
    // takes infinite lights only.
    bool samplesLights() const override {
        return fromLights() || source_ == CandidateSource::Mixture;
    }

  private:
    bool fromLights() const {
        return source_ == CandidateSource::Light || source_ == CandidateSource::LightProxy;
    }
    // The candidates of one shading point in the order its samples draw them: candidate j of
    // sample i is draw offset + i·stride + j of `repeats`, exactly as drawCandidate() gives it.
    // Light candidates are drawn in batches that run across samples (ShadingPoint::
    // sampleLights), so that the lights overlap their table reads; others one at a time.
    class CandidateStream {
      public:
        CandidateStream(const RisEstimator& estimator, ShadingPoint& point, uint32_t samples,
                        uint32_t candidates, uint32_t stride, uint32_t offset, uint32_t repeats)
            : estimator_(estimator),
              point_(point),
              total_(samples * candidates),
              candidates_(candidates),
              stride_(stride),
              offset_(offset),
              repeats_(repeats) {}
        // The next candidate; false when none was drawn (it still counts in M).
        bool next(Candidate* candidate);

      private:
        static constexpr uint32_t kBatch = 16;
        uint32_t repeatAt(uint32_t k) const {
            return offset_ + (k / candidates_) * stride_ + k % candidates_;
        }

        const RisEstimator& estimator_;
        ShadingPoint& point_;
        uint32_t total_, candidates_, stride_, offset_, repeats_;
        uint32_t position_ = 0, buffered_ = 0, used_ = 0;
        std::array<LightDraw, kBatch> batch_{};
    };

    const LightStandIns* standIns() const {
        return source_ == CandidateSource::LightProxy ? &standIns_ : nullptr;
    }
    bool candidateFrom(const ShadingPoint& point, const LightDraw& draw,
                       Candidate* candidate) const;
    bool drawCandidate(ShadingPoint& point, uint32_t repeat, uint32_t repeats,
                       Candidate* candidate) const;
    bool drawFromMixture(ShadingPoint& point, uint32_t repeat, uint32_t repeats,
                         Candidate* candidate) const;
    // The candidate's contribution f·(1/density): visibility (or the emission found) decided.
    Rgb finish(ShadingPoint& point, const Candidate& candidate, float density) const;

    CandidateSource source_;
    CandidateCounts counts_, maxCounts_;
    LightStandIns standIns_;  // `light_proxy`: the scene's lights' (prepare)
};

}  // namespace rr::ris
