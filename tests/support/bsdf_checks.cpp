#include "support/bsdf_checks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "support/histograms.h"
#include "support/test_random.h"

namespace rr::test {

Vec3 directionFromDegrees(double thetaDegrees, double phiDegrees) {
    const double t = thetaDegrees * M_PI / 180, p = phiDegrees * M_PI / 180;
    return Vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)),
                float(std::cos(t)));
}

std::string describe(const Vec3& w) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "(%.6f, %.6f, %.6f)", w.x, w.y, w.z);
    return buffer;
}

namespace {

bool isFiniteRgb(const Rgb& c) {
    return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}

bool relativelyClose(double a, double b, double tolerance = 1e-3) {
    return std::abs(a - b) <= tolerance * std::max({std::abs(a), std::abs(b), 1e-12});
}

// Checks one non-specular sample against eval() and pdf(); returns "" or what differs.
std::string checkWeight(const Material& m, const ShadingContext& ctx, const Vec3& wo,
                        const BsdfSample& s) {
    const float pdf = m.pdf(ctx, wo, s.wi);
    if (!relativelyClose(s.pdf, pdf))
        return "sample pdf " + std::to_string(s.pdf) + " vs pdf() " + std::to_string(pdf);
    if (!(pdf > 0)) return "sampled a direction with pdf() = 0";
    const Rgb f = m.eval(ctx, wo, s.wi);
    for (int c = 0; c < 3; ++c)
        if (!relativelyClose(s.weight[c], double(f[c]) / pdf))
            return "weight " + std::to_string(s.weight[c]) + " vs eval/pdf " +
                   std::to_string(double(f[c]) / pdf);
    return "";
}

}  // namespace

BsdfSamplingRun sampleBsdf(const Material& material, const ShadingContext& ctx, const Vec3& wo,
                           uint64_t seed, int samples, const BsdfHistogramLayout& layout) {
    const Frame cap(normalize(layout.axis));
    const double zMin = std::cos(layout.capDegrees * M_PI / 180);
    DirectionHistogram histogram(layout.zCells, layout.phiCells, std::max(-1.0, zMin));
    BsdfSamplingRun run;
    for (int i = 0; i < samples; ++i) {
        BsdfSample s;
        if (!material.sample(ctx, wo, uniform(seed, i, 2), uniform2(seed, i), &s)) {
            ++run.declined;
            continue;
        }
        if (!isFiniteRgb(s.weight) || !isFinite(s.wi) || std::abs(length(s.wi) - 1) > 1e-4f) {
            ++run.nonFinite;
            continue;
        }
        if (s.isSpecular()) {
            ++run.specular;
            continue;
        }
        if (const std::string why = checkWeight(material, ctx, wo, s); !why.empty()) {
            if (run.weightMismatches++ == 0) run.firstMismatch = why + " at wi = " + describe(s.wi);
        }
        histogram.add(cap.toLocal(s.wi));
    }
    // pdf() is the density of the non-specular directions sample() returns, relative to all
    // its draws: a sampler may decline a draw (a lobe direction below the surface, a sample
    // of zero value) or return a specular lobe, and pdf() then integrates to less than one.
    // Those draws join the directions outside the cap in the extra cell, which expects the
    // mass pdf() does not hold: for the whole sphere and a sampler that never declines, zero
    // up to the integration error. That error (~10⁻⁶ of the total) is the least the cell can
    // be told to expect, so that a draw declined on a set of measure zero (a direction that
    // rounds onto the horizon) is not taken for a sample where the density is zero.
    const double drawn = samples - run.nonFinite;
    std::vector<double> expected = histogram.expected(
        [&](const Vec3& w) { return double(material.pdf(ctx, wo, cap.toWorld(w))); }, drawn);
    double inside = 0;
    for (size_t i = 0; i + 1 < expected.size(); ++i)
        inside += expected[i];
    expected.back() = std::max(1e-6 * drawn, drawn - inside);
    std::vector<double> observed = histogram.counts();
    observed.back() += run.declined + run.specular;
    run.outcome = chi2GoodnessOfFit(observed, expected);
    return run;
}

Rgb directionalAlbedo(const Material& material, const ShadingContext& ctx, const Vec3& wo,
                      uint64_t seed, int samples) {
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < samples; ++i) {
        BsdfSample s;
        if (!material.sample(ctx, wo, uniform(seed, i, 2), uniform2(seed, i), &s)) continue;
        for (int c = 0; c < 3; ++c)
            sum[c] += s.weight[c];
    }
    return Rgb(float(sum[0] / samples), float(sum[1] / samples), float(sum[2] / samples));
}

double reciprocityError(const Material& material, const ShadingContext& ctx, uint64_t seed,
                        int pairs) {
    auto randomDirection = [&](int i, int dim) {
        const double z = 2.0 * uniform(seed, i, dim) - 1.0;
        const double phi = 2 * M_PI * uniform(seed, i, dim + 1);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        return Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
    };
    double worst = 0;
    for (int i = 0; i < pairs; ++i) {
        Vec3 wo = randomDirection(i, 0), wi = randomDirection(i, 2);
        if (wo.z * wi.z <= 0) wi.z = -wi.z;  // reflection: both on one side
        if (std::abs(wo.z) < 1e-3f || std::abs(wi.z) < 1e-3f) continue;
        const Rgb a = material.eval(ctx, wo, wi), b = material.eval(ctx, wi, wo);
        for (int c = 0; c < 3; ++c) {
            const double fa = a[c] / std::abs(wi.z), fb = b[c] / std::abs(wo.z);
            const double scale = std::max({std::abs(fa), std::abs(fb), 1e-12});
            worst = std::max(worst, std::abs(fa - fb) / scale);
        }
    }
    return worst;
}

}  // namespace rr::test
