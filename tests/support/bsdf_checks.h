// Checks every material must pass (Mitsuba's shared χ² tooling, pbrt's energy check), in one
// place so that each material's test is a list of parameters and incident directions:
//  - χ² of sample() against pdf(), with an optional zoom onto a narrow lobe;
//  - the sample weight equals eval/pdf and is finite;
//  - the directional albedo estimated from sample() weights is at most 1 + 1 %;
//  - reciprocity of eval/|cos θi|.
#pragma once

#include <cstdint>
#include <string>

#include "math/frame.h"
#include "scene/material.h"
#include "support/chi2.h"

namespace rr::test {

// Where to histogram sampled directions: a cap of half-angle `capDegrees` around `axis`
// (local shading frame), divided into zCells × phiCells equal-solid-angle cells, plus one cell
// for everything outside the cap, together with the declined and specular samples, whose
// expected count is the complement of pdf()'s mass in the cap. The default is the whole
// sphere. Zoom onto a narrow lobe (exponent 1000, roughness 0.001) by centring the cap on
// its peak, so that the cells resolve it.
struct BsdfHistogramLayout {
    Vec3 axis = Vec3(0, 0, 1);
    double capDegrees = 180;
    int zCells = 41;  // odd: on the whole sphere the horizon falls inside a cell
    int phiCells = 60;
};

struct BsdfSamplingRun {
    Chi2Outcome outcome;
    int declined = 0;           // sample() returned false (counted in the last cell)
    int specular = 0;           // samples of specular lobes (not histogrammed)
    int nonFinite = 0;          // non-finite weight or direction, or a non-unit direction
    int weightMismatches = 0;   // weight ≠ eval/pdf or pdf ≠ pdf() beyond 1e-3 relative
    std::string firstMismatch;  // description of the first mismatch
};

// Draws `samples` directions for `wo` and compares their histogram with pdf(wo, ·).
BsdfSamplingRun sampleBsdf(const Material& material, const ShadingContext& ctx, const Vec3& wo,
                           uint64_t seed, int samples = 1000000,
                           const BsdfHistogramLayout& layout = {});

// Directional albedo ∫ f·|cos θi| dωi for `wo`, estimated as the mean sample() weight over
// `samples` draws (per channel; declined samples count as zero).
Rgb directionalAlbedo(const Material& material, const ShadingContext& ctx, const Vec3& wo,
                      uint64_t seed, int samples = 100000);

// Largest relative violation of f(wo, wi) = f(wi, wo) (f = eval/|cos θi|) over `pairs` random
// direction pairs on the same side; relative to max(f, 1e-3 · the larger of the two).
double reciprocityError(const Material& material, const ShadingContext& ctx, uint64_t seed,
                        int pairs = 20000);

// Unit direction from polar angle θ and azimuth φ in degrees (local frame).
Vec3 directionFromDegrees(double thetaDegrees, double phiDegrees);
std::string describe(const Vec3& w);

}  // namespace rr::test
