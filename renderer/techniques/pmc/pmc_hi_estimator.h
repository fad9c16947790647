// `pmc_hi`: population Monte Carlo for the hemispheric integral of direct lighting (Lai et al.
// 2007 §5), a direct-lighting estimator (integrators/direct_lighting_estimator.h) usable by
// `direct` and at every vertex of `path_mis`.
//
// Per shading point, T iterations of a population of N samples from the mixture kernel
// (eq. 7)  K = α_BSDF h_BSDF + Σ_k α_Lk h_Lk + α_cone h_cone(d, β):
// the BSDF's own sampling, one component per light (its own sampler, no selection), and
// directions uniform in the cone of half-angle β about d. With many lights (`light_components`
// "one", or "auto" beyond kMaxLights) one component stands for all of them: the integrator's
// light sampling, selection included (§7 suggests a single component for all lights, relying
// on the cone to find the visible ones). Per iteration:
//  - counts per component by deterministic mixture sampling (⌊Nα_k⌋ plus a systematic
//    residual, mixture_allocation.h), so E[n_k] = N α_k;
//  - each sample x (a point on a light, or the emitter a direction finds) is weighed by the
//    full mixture, w = f(x)/K(x) (eq. 8, f = Fs·|cos θ|·Le·V), where K sums every
//    component's density of x: the BSDF's and the cone's of its direction, and the density
//    of the light x lies on (for a direction to the infinite lights, each of theirs);
//  - the iteration's estimate is (1/N) Σ w, unbiased given α;
//  - then the kernel adapts to the population (eq. 9): α_k ∝ Σ_{i∈S_k} luminance(w_i), d the
//    w-weighted mean direction, β the w-weighted RMS angle about d (in [kMinConeAngle, π/2]);
//    at the first adaptation that found something (normally after iteration 0) the cone gets
//    α = `cone_share` and the others are scaled by 1 − cone_share; α_BSDF and every α_Lk are
//    floored at `floor` before renormalising (so they stay above floor/(1 + floor·m)), so the
//    components that cover the integrand never die.
// Iteration 0 has equal α over the BSDF and the lights, the cone off; with `feedback` (§6.1),
// at a pixel sample's first hit under pmc_ip, the pixel's mean final α of the earlier
// iterations instead (the cone off, the floors applied): fixed before the iteration, so the
// estimate stays unbiased. The estimate is the unweighted mean of the T iterations'
// estimates: fixed weights, so unbiased. Emission that the integrator's own BSDF samples find
// is excluded (this estimate covers it all). Area and infinite lights only (a point light has
// no density over directions to mix); surfaces in scenes without media.
#pragma once

#include <cstdint>
#include <vector>

#include "integrators/direct_lighting_estimator.h"

namespace rr::pmc {

enum class LightComponents : uint8_t { Auto, Each, One };

struct PmcHiSettings {
    uint32_t samples = 0;  // N per iteration; 0: twice the components (2m, §5)
    uint32_t iterations = 2;
    double coneShare = 0.2;  // α_cone after iteration 0
    double floor = 0.05;     // least α of the BSDF and of each light
    LightComponents lightComponents = LightComponents::Auto;
    bool alphaMaps = false;  // record α^(T) at first hits (fig. 7)
    // §6.1: record α^(T) at first hits, and start a first hit's iteration 0 from the pixel's
    // mean α^(T) as committed at the last PMC-IP iteration boundary.
    bool feedback = false;
};

class PmcHiEstimator final : public DirectLightingEstimator {
  public:
    // The most lights that get a component each.
    static constexpr uint32_t kMaxLights = 16;
    static constexpr float kMinConeAngle = 1e-3f;
    static constexpr uint32_t kMaxPopulation = 256;

    explicit PmcHiEstimator(const PmcHiSettings& settings) : settings_(settings) {}

    std::string name() const override { return "pmc_hi"; }
    nlohmann::json parameters() const override;
    uint32_t lightSamples() const override { return populationSize() * settings_.iterations; }
    FoundEmission foundEmission() const override { return FoundEmission::Excluded; }
    bool worksInMedia() const override { return false; }
    void prepare(const Scene& scene, const std::string& pointer) override;
    void estimate(ShadingPoint& point) const override;
    // With alpha_maps (or feedback, which starts from them): the α each estimate would use
    // next, α^(T) after its T iterations (fig. 7 shows α^(2)), per component:
    // pmc_hi.alpha.bsdf, .light<index> (or .lights, one for all), .cone.
    PixelRecordLayout pixelRecords() const override;

    // m: the BSDF, one per light (or one for all), the cone.
    uint32_t components() const { return lightComponents() + 2; }
    uint32_t lightComponents() const { return oneForAllLights_ ? 1 : uint32_t(lights_.size()); }
    uint32_t populationSize() const {
        return settings_.samples > 0 ? settings_.samples : 2 * components();
    }

    // For the χ² test of the mixture (tests/pmc/test_pmc_hi_mixture.cpp): the kernel with
    // fixed parameters, one population drawn from it as estimate() draws an iteration's, and
    // the density of the samples it finds.
    struct MixtureParameters {
        std::vector<double> alpha;  // components(): the BSDF, each light (or all), the cone
        Vec3 coneAxis{0, 0, 1};
        float coneAngle = 0;  // β, radians; alpha's last entry must be 0 when there is no cone
    };
    struct MixtureSample {
        uint32_t component;
        Vec3 direction;
        float density;  // K (eq. 8's denominator)
    };
    // The samples of one population of `n` that found emission (f·Le·V > 0).
    std::vector<MixtureSample> drawPopulation(ShadingPoint& point, const MixtureParameters& p,
                                              uint32_t n) const;
    // K of the sample a draw in direction `wi` would find: 0 where f·Le is zero.
    float mixtureDensity(ShadingPoint& point, const MixtureParameters& p, const Vec3& wi) const;

  private:
    struct Kernel;
    struct Draw;
    template <class Found>
    uint32_t drawIteration(ShadingPoint& point, const Kernel& kernel, uint32_t t, uint32_t n,
                           uint32_t iterations, Draw* draws, Found&& found) const;
    Kernel kernelOf(const MixtureParameters& p) const;
    bool draw(ShadingPoint& point, const Kernel& kernel, uint32_t component, uint32_t repeat,
              uint32_t repeats, Draw* out) const;
    bool drawLightPoint(ShadingPoint& point, uint32_t component, uint32_t repeat, uint32_t repeats,
                        Draw* d) const;
    Rgb findEmission(ShadingPoint& point, Draw* d) const;
    float density(const ShadingPoint& point, const Kernel& kernel, const Draw& d) const;
    void adapt(const Kernel& previous, const Draw* draws, uint32_t count, Kernel* next) const;
    Kernel initialKernel(const ShadingPoint& point) const;
    void applyFloors(Kernel* kernel) const;
    bool records() const { return settings_.alphaMaps || settings_.feedback; }

    PmcHiSettings settings_;
    std::vector<const Light*> lights_;
    std::vector<const Light*> infiniteLights_;
    bool oneForAllLights_ = false;
};

}  // namespace rr::pmc
