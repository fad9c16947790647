// The resampling machinery of RIS (Talbot et al. 2005) on problems whose answers are known in
// closed form: the reservoir's selection probabilities, random rounding, eq. (2)'s variance
// for several M, eq. (2)'s terms, and the M/N choice of eqs. (3), (4) and §4.2.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "support/chi2.h"
#include "support/test_random.h"
#include "techniques/ris/candidate_counts.h"
#include "techniques/ris/reservoir.h"

namespace rr::test {
namespace {

using ris::CandidateCosts;
using ris::CandidateCounts;

// A candidate on [0, 1]: x ~ p = 1 with target ĝ(x) = 1 + x.
struct LineCandidate {
    float x = 0;
    float target = 0;
    float pdf = 1;
};
float integrand(float x) {
    return x * x;
}  // f(x) = x², I = 1/3

// Closed forms of eq. (2)'s terms for f = x², ĝ = 1 + x, p = 1 on [0, 1]:
//   e1 = (∫x²)² = 1/9, e3 = ∫x⁴ = 1/5,
//   e2 = ∫x⁴/(1+x) · ∫(1+x) = (ln 2 − 7/12) · 3/2.
const double kE1 = 1.0 / 9, kE3 = 1.0 / 5, kE2 = (std::log(2.0) - 7.0 / 12) * 1.5;

double eq2Variance(double m, double n) {
    return ((kE3 - kE2) / m + (kE2 - kE1)) / n;
}

TEST(Reservoir, KeepsEachCandidateWithProbabilityProportionalToItsWeight) {
    const std::vector<float> weights = {0.5f, 3, 0, 1.25f, 7, 0.01f, 2, 4};
    const int trials = 200000;
    std::vector<double> observed(weights.size(), 0), expected(weights.size(), 0),
        uniformExpected(weights.size(), 0);
    double sum = 0;
    for (float w : weights)
        sum += w;
    for (int t = 0; t < trials; ++t) {
        ris::WeightedReservoir<int> reservoir;
        for (size_t j = 0; j < weights.size(); ++j)
            reservoir.offer(int(j), weights[j], uniform(7, t, j));
        ASSERT_FALSE(reservoir.empty());
        observed[reservoir.kept()] += 1;
    }
    for (size_t j = 0; j < weights.size(); ++j) {
        expected[j] = trials * weights[j] / sum;
        uniformExpected[j] = double(trials) / weights.size();
    }
    const Chi2Family family(2);
    family.expectFits(chi2GoodnessOfFit(observed, expected));
    family.expectRejects(chi2GoodnessOfFit(observed, uniformExpected), "uniform selection");
}

TEST(Reservoir, AllZeroWeightsKeepNothing) {
    ris::WeightedReservoir<int> reservoir;
    reservoir.offer(1, 0, 0.5f);
    reservoir.offer(2, 0, 0.0f);
    EXPECT_TRUE(reservoir.empty());
    EXPECT_EQ(reservoir.offered(), 2u);
}

// Found by `make stress` (the `ris` integrator crashed on a scene with a point light): for a
// denormal weight (ĝ/p = 1e-44) the selection u times the weight rounds to the weight in float,
// so the first candidate of positive weight was not kept and the reservoir, non-empty, held a
// default candidate.
TEST(Reservoir, KeepsTheFirstCandidateWhateverTheSelection) {
    for (float w : {9.8e-45f, 5.6e-45f, 1e-30f, 1.0f, 1e30f})
        for (float u : {0.5f, 0.95f, std::nextafter(1.0f, 0.0f)}) {
            ris::WeightedReservoir<int> reservoir;
            reservoir.offer(7, 0, 0.5f);
            reservoir.offer(8, w, u);
            ASSERT_FALSE(reservoir.empty());
            EXPECT_EQ(reservoir.kept(), 8) << w << " " << u;
        }
}

// Fig. 1's problem: p uniform on [0, π/2], ĝ(θ) = cos θ + sin⁴(6θ). Resampling M = 2 candidates
// gives Y the density p_Y(y) = p(y)·w(y)·E[2 / (w(y) + w(X))], X ~ p, w = ĝ/p (the reservoir keeps
// y with probability w(y)/(w(y) + w(X)), and either candidate can be y). 10⁶ draws of Y must
// fit it (χ², 64 bins, expected counts by quadrature), and must not fit p (M = 1) or ĝ
// normalised (M = ∞): the interpolation fig. 1 shows.
double fig1Target(double theta) {
    return std::cos(theta) + std::pow(std::sin(6 * theta), 4);
}

TEST(Resampling, FigureOneDensityWithTwoCandidatesIsExact) {
    const double halfPi = M_PI / 2, p = 1 / halfPi;
    constexpr int kBins = 64, kDraws = 1000000, kInner = 2048, kSub = 16;
    struct AngleCandidate {
        float theta = 0, target = 0, pdf = 0;
    };
    std::vector<double> observed(kBins, 0);
    for (int t = 0; t < kDraws; ++t) {
        auto draw = [&](uint32_t j, AngleCandidate* c) {
            c->theta = float(halfPi) * uniform(21, t, 2 * j);
            c->target = float(fig1Target(c->theta));
            c->pdf = float(p);
            return true;
        };
        auto select = [&](uint32_t j) { return uniform(21, t, 2 * j + 1); };
        AngleCandidate y;
        float density;
        ASSERT_TRUE(ris::resample(2u, draw, select, &y, &density));
        observed[std::min(kBins - 1, int(y.theta / halfPi * kBins))] += 1;
    }
    // E[2 / (w(y) + w(X))] by the midpoint rule over X.
    auto density = [&](double y) {
        double e = 0;
        for (int k = 0; k < kInner; ++k)
            e += 2 / (fig1Target(y) / p + fig1Target((k + 0.5) / kInner * halfPi) / p) / kInner;
        return p * fig1Target(y) / p * e;
    };
    const double gIntegral = 1 + 3 * M_PI / 16;  // ∫ cos θ + sin⁴ 6θ over [0, π/2]
    std::vector<double> exact(kBins, 0), source(kBins, 0), target(kBins, 0);
    for (int b = 0; b < kBins; ++b) {
        const double width = halfPi / kBins;
        for (int k = 0; k < kSub; ++k) {
            const double y = (b + (k + 0.5) / kSub) * width;
            exact[b] += kDraws * density(y) * width / kSub;
            target[b] += kDraws * fig1Target(y) / gIntegral * width / kSub;
        }
        source[b] = double(kDraws) / kBins;
    }
    const Chi2Family family(3);
    family.expectFits(chi2GoodnessOfFit(observed, exact));
    family.expectRejects(chi2GoodnessOfFit(observed, source), "M = 1 (p)");
    family.expectRejects(chi2GoodnessOfFit(observed, target), "M = infinity (g normalised)");
}

TEST(RoundRandomly, KeepsTheExpectation) {
    const int n = 400000;
    const double xs[] = {15.75, 10.635, 1.0, 3.0, 1.001};
    const double threshold = zThreshold(sidakAlpha(0.01, 5));
    for (double x : xs) {
        double sum = 0, sumSquares = 0;
        for (int i = 0; i < n; ++i) {
            const uint32_t k = ris::roundRandomly(x, uniform(11, i));
            ASSERT_TRUE(k == uint32_t(std::floor(x)) || k == uint32_t(std::ceil(x))) << x;
            sum += k;
            sumSquares += double(k) * k;
        }
        const double mean = sum / n, variance = sumSquares / n - mean * mean;
        if (variance == 0) {
            EXPECT_EQ(mean, x);
            continue;
        }
        EXPECT_LT(std::abs(mean - x) / std::sqrt(variance / n), threshold) << x;
    }
}

// Draws of eq. (1) with N = 1 on the 1-D problem, with independent candidates.
struct Moments {
    double mean = 0, variance = 0, fourth = 0;  // central moments of the estimates
    int n = 0;
};

Moments risEstimates(uint32_t m, int n, uint64_t seed) {
    std::vector<double> values(n);
    for (int t = 0; t < n; ++t) {
        auto draw = [&](uint32_t j, LineCandidate* c) {
            c->x = uniform(seed, t, 2 * j);
            c->target = 1 + c->x;
            c->pdf = 1;
            return true;
        };
        auto select = [&](uint32_t j) { return uniform(seed, t, 2 * j + 1); };
        LineCandidate y;
        float density;
        values[t] = ris::resample(m, draw, select, &y, &density) ? integrand(y.x) / density : 0;
    }
    Moments mo;
    mo.n = n;
    for (double v : values)
        mo.mean += v / n;
    for (double v : values) {
        const double d = (v - mo.mean) * (v - mo.mean);
        mo.variance += d / (n - 1);
        mo.fourth += d * d / n;
    }
    return mo;
}

// z of a measured variance against `expected`: the sample variance's standard error is
// √((μ4 − σ⁴)/n).
double varianceZ(const Moments& mo, double expected) {
    return (mo.variance - expected) / std::sqrt((mo.fourth - mo.variance * mo.variance) / mo.n);
}

TEST(Eq2, MeasuredVarianceOfResampledImportanceSamplingMatchesEq2) {
    const uint32_t ms[] = {1, 2, 4, 8, 32};
    const double threshold = zThreshold(sidakAlpha(0.01, 2 * 5));
    for (uint32_t m : ms) {
        const Moments mo = risEstimates(m, 400000, 100 + m);
        const double zMean = (mo.mean - 1.0 / 3) / std::sqrt(mo.variance / mo.n);
        const double zVariance = varianceZ(mo, eq2Variance(m, 1));
        std::printf("M = %2u: mean %.5f (z %.2f), variance %.5f, eq. (2) %.5f (z %.2f)\n", m,
                    mo.mean, zMean, mo.variance, eq2Variance(m, 1), zVariance);
        EXPECT_LT(std::abs(zMean), threshold) << "M = " << m;
        EXPECT_LT(std::abs(zVariance), threshold) << "M = " << m;
    }
}

// The test can tell eq. (2)'s M = 8 from plain importance sampling's e3 − e1.
TEST(Eq2, NegativeControlRejectsTheImportanceSamplingVariance) {
    const Moments mo = risEstimates(8, 400000, 108);
    EXPECT_GT(std::abs(varianceZ(mo, kE3 - kE1)), zThreshold(0.01));
}

TEST(VarianceTerms, MatchTheirClosedFormsByQuadrature) {
    ris::VarianceTerms terms;
    const int k = 100000;  // midpoint rule: the error is O(1/k²)
    for (int i = 0; i < k; ++i) {
        const float x = (i + 0.5f) / k;
        terms.add(Rgb(integrand(x)), 1 + x, 1);
    }
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(terms.e1()[c], kE1, 1e-5 * kE1);
        EXPECT_NEAR(terms.e2()[c], kE2, 1e-5 * kE2);
        EXPECT_NEAR(terms.e3()[c], kE3, 1e-5 * kE3);
    }
    // Grey: the l2 lengths are √3 times one channel's.
    EXPECT_NEAR(terms.sourceExcess(), std::sqrt(3.0) * (kE3 - kE2), 1e-4 * (kE3 - kE2));
    EXPECT_NEAR(terms.targetExcess(), std::sqrt(3.0) * (kE2 - kE1), 1e-4 * (kE2 - kE1));
}

// The variance × time product that eq. (3) minimises.
double costOfVariance(double m, const CandidateCosts& c) {
    return (m * c.tX + c.tY) * ((kE3 - kE2) / m + (kE2 - kE1));
}

TEST(CandidateCounts, OptimalCandidatesMinimiseVarianceTimesTime) {
    ris::VarianceTerms terms;
    const int k = 100000;
    for (int i = 0; i < k; ++i) {
        const float x = (i + 0.5f) / k;
        terms.add(Rgb(integrand(x)), 1 + x, 1);
    }
    for (const CandidateCosts costs :
         {CandidateCosts{1, 15.75}, CandidateCosts{1, 2.1}, CandidateCosts{3, 1}}) {
        const double m = ris::optimalCandidates(terms, costs, 1024);
        EXPECT_NEAR(m, std::sqrt((kE3 - kE2) / (kE2 - kE1) * costs.tY / costs.tX), 1e-3 * m);
        EXPECT_LE(costOfVariance(m, costs), costOfVariance(m * 1.05, costs));
        EXPECT_LE(costOfVariance(m, costs), costOfVariance(m / 1.05, costs));
    }
}

TEST(CandidateCounts, RobustChoiceReproducesFigure4sNumbers) {
    // Fig. 4: T_Y/T_X = 15.75 and the time of 20 plain light samples give M = 15.75, N = 10.64.
    const CandidateCosts costs{1e-8, 15.75e-8};
    const CandidateCounts counts =
        ris::countsWithinBudget(ris::robustCandidates(costs), costs, 20, 1024);
    EXPECT_NEAR(counts.m, 15.75, 1e-9);
    EXPECT_NEAR(counts.n, 10.635, 1e-3);
    // Every choice fills the budget exactly: M N T_X + N T_Y = 20 (T_X + T_Y).
    EXPECT_NEAR(counts.m * counts.n * costs.tX + counts.n * costs.tY, 20 * (costs.tX + costs.tY),
                1e-12);
}

TEST(CandidateCounts, ClampsKeepBothCountsAtLeastOneWithinTheBudget) {
    const CandidateCosts costs{1, 4};
    // A wanted M too large for N ≥ 1: N = 1 and M takes the rest of the budget, (10·5 − 4)/1.
    CandidateCounts c = ris::countsWithinBudget(500, costs, 10, 1024);
    EXPECT_EQ(c.n, 1);
    EXPECT_NEAR(c.m, 46, 1e-9);
    // M below 1 becomes 1, which is plain light sampling with the whole budget.
    c = ris::countsWithinBudget(0.2, costs, 10, 1024);
    EXPECT_NEAR(c.m, 1, 1e-9);
    EXPECT_NEAR(c.n, 10, 1e-9);
    // The cap on M holds.
    c = ris::countsWithinBudget(500, costs, 1000, 64);
    EXPECT_LE(c.m, 64);
}

}  // namespace
}  // namespace rr::test
