// Tests of Distribution1D (sampling/distribution1d.h): the pmf, zero and all-zero weights,
// χ² of the sampled indices, and the remapped u that is handed on for reuse.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

#include "sampling/distribution1d.h"
#include "sampling/distribution2d.h"
#include "sampling/hash.h"
#include "support/chi2.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

// Every χ² run in this file: indices (2 distributions), pooled remapped u, joint (index,
// remapped u), and 2 negative controls.
constexpr int kRuns = 6;
const Chi2Family kChi2(kRuns);
const double kAlpha = kChi2.alpha();
constexpr int kSamples = 1000000;

// 50 weights 1..7 with zeros at every tenth entry from 3 on, and at both ends.
std::vector<float> mixedWeights() {
    std::vector<float> w(50);
    for (size_t i = 0; i < w.size(); ++i)
        w[i] = i % 10 == 3 ? 0.0f : float(1 + i % 7);
    w.front() = 0;
    w.back() = 0;
    return w;
}

// 1000 weights spanning six orders of magnitude.
std::vector<float> wideWeights() {
    std::vector<float> w(1000);
    for (size_t i = 0; i < w.size(); ++i)
        w[i] = std::pow(10.0f, 6.0f * uniform(5, i) - 3.0f);
    return w;
}

std::vector<double> normalized(const std::vector<float>& w) {
    const double total = std::accumulate(w.begin(), w.end(), 0.0);
    std::vector<double> p;
    for (float x : w)
        p.push_back(double(x) / total);
    return p;
}

// u values that stress the search: both ends of [0,1) and the floats around every CDF step.
std::vector<float> edgeUs(const std::vector<float>& weights) {
    std::vector<float> us = {0.0f, 0x1p-24f, 0.5f, 1.0f - 0x1p-24f};
    const std::vector<double> p = normalized(weights);
    double cdf = 0;
    for (double x : p) {
        cdf += x;
        const float c = float(cdf);
        for (float u : {std::nextafter(c, 0.0f), c, std::nextafter(c, 1.0f)})
            if (u >= 0.0f && u < 1.0f) us.push_back(u);
    }
    return us;
}

Chi2Outcome indexChi2(const Distribution1D& d, const std::vector<double>& pmf, uint64_t seed) {
    std::vector<double> counts(pmf.size(), 0.0), expected(pmf.size());
    for (int i = 0; i < kSamples; ++i)
        counts[d.sample(uniform(seed, i))] += 1;
    for (size_t i = 0; i < pmf.size(); ++i)
        expected[i] = pmf[i] * kSamples;
    return chi2GoodnessOfFit(counts, expected);
}

// Joint histogram of (index, remapped u in 20 cells): tests P(index) and the conditional
// uniformity of the remapped u at once.
Chi2Outcome jointChi2(const Distribution1D& d, const std::vector<double>& pmf, uint64_t seed,
                      bool useRawU) {
    constexpr int kCells = 20;
    std::vector<double> counts(pmf.size() * kCells, 0.0), expected(counts.size());
    for (int i = 0; i < kSamples; ++i) {
        const float u = uniform(seed, i);
        float r;
        const int index = d.sample(u, nullptr, &r);
        if (useRawU) r = u;
        counts[size_t(index) * kCells + std::min(int(r * kCells), kCells - 1)] += 1;
    }
    for (size_t i = 0; i < counts.size(); ++i)
        expected[i] = pmf[i / kCells] * kSamples / kCells;
    return chi2GoodnessOfFit(counts, expected);
}

TEST(Distribution1D, PmfMatchesNormalizedWeights) {
    const std::vector<std::vector<float>> cases = {
        {1, 2, 3, 4}, {0.5f}, {1e-6f, 1.0f, 1e6f}, {0, 0, 7, 0}, mixedWeights(), wideWeights()};
    for (const std::vector<float>& w : cases) {
        const Distribution1D d(w);
        ASSERT_EQ(d.size(), int(w.size()));
        const std::vector<double> p = normalized(w);
        double sum = 0;
        for (int i = 0; i < d.size(); ++i) {
            EXPECT_NEAR(d.pmf(i), p[i], 1e-6 * p[i]) << "entry " << i << " of " << w.size();
            sum += d.pmf(i);
        }
        EXPECT_NEAR(sum, 1.0, 1e-5);
    }
}

TEST(Distribution1D, AllZeroWeightsAreUniform) {
    for (int n : {1, 2, 5, 100}) {
        const std::vector<float> w(n, 0.0f);
        const Distribution1D d(w);
        std::vector<int> counts(n, 0);
        const int m = 1000 * n;
        for (int k = 0; k < m; ++k) {
            float pmf;
            const int i = d.sample((k + 0.5f) / m, &pmf);
            ASSERT_GE(i, 0);
            ASSERT_LT(i, n);
            EXPECT_FLOAT_EQ(pmf, 1.0f / n);
            ++counts[i];
        }
        for (int i = 0; i < n; ++i) {
            EXPECT_FLOAT_EQ(d.pmf(i), 1.0f / n);
            EXPECT_NEAR(counts[i], 1000, 1) << "n = " << n << ", index " << i;
        }
    }
}

// A dense sweep of u plus the floats around every CDF step never returns a zero-weight entry,
// and the pmf reported by sample() is the pmf of the returned index.
TEST(Distribution1D, ZeroWeightEntriesAreNeverSampled) {
    const std::vector<std::vector<float>> cases = {
        {0, 1},         {1, 0},        {0, 0, 1, 0, 0}, {1, 0, 0, 1}, {0, 3, 0, 0, 2, 0},
        {1e-30f, 0, 1}, mixedWeights()};
    for (const std::vector<float>& w : cases) {
        const Distribution1D d(w);
        std::vector<float> us = edgeUs(w);
        for (int k = 0; k < 100000; ++k)
            us.push_back(float(k) / 100000);
        for (float u : us) {
            float pmf = -1, r = -1;
            const int i = d.sample(u, &pmf, &r);
            ASSERT_GE(i, 0);
            ASSERT_LT(i, d.size());
            ASSERT_GT(w[i], 0.0f) << "u = " << u << " gave zero-weight entry " << i << " of "
                                  << w.size();
            ASSERT_EQ(pmf, d.pmf(i));
            ASSERT_TRUE(r >= 0.0f && r < 1.0f) << "u = " << u << ": remapped " << r;
        }
    }
}

// Inverse-CDF sampling: the index is non-decreasing in u, and u = cdf(i) + r·pmf(i).
TEST(Distribution1D, SamplingInvertsTheCdf) {
    for (const std::vector<float>& w : {mixedWeights(), wideWeights()}) {
        const Distribution1D d(w);
        const std::vector<double> p = normalized(w);
        std::vector<double> cdf(p.size() + 1, 0.0);
        for (size_t i = 0; i < p.size(); ++i)
            cdf[i + 1] = cdf[i] + p[i];
        int previous = 0;
        float previousR = 0;
        std::vector<float> us = edgeUs(w);
        for (int k = 0; k < 200000; ++k)
            us.push_back(float(k) / 200000);
        std::sort(us.begin(), us.end());
        for (float u : us) {
            float r;
            const int i = d.sample(u, nullptr, &r);
            ASSERT_GE(i, previous) << "u = " << u;
            if (i == previous) {
                ASSERT_GE(r, previousR) << "u = " << u;
            }
            ASSERT_NEAR(cdf[i] + r * p[i], u, 1e-6) << "u = " << u << ", index " << i;
            previous = i;
            previousR = r;
        }
    }
}

TEST(Distribution1D, SingleEntryReturnsUUnchanged) {
    const std::vector<float> w = {3.0f};
    const Distribution1D d(w);
    for (float u : {0.0f, 0.25f, 0.7f, 1.0f - 0x1p-24f}) {
        float pmf, r;
        EXPECT_EQ(d.sample(u, &pmf, &r), 0);
        EXPECT_EQ(pmf, 1.0f);
        EXPECT_EQ(r, u);
    }
}

TEST(Distribution1DChi2, SampledIndicesFollowThePmf) {
    const std::vector<float> w = mixedWeights();
    kChi2.expectFits(indexChi2(Distribution1D(w), normalized(w), 1), "indices, 50 mixed weights");
}

TEST(Distribution1DChi2, SampledIndicesFollowAWidePmf) {
    const std::vector<float> w = wideWeights();
    kChi2.expectFits(indexChi2(Distribution1D(w), normalized(w), 2), "indices, 1000 wide weights");
}

TEST(Distribution1DChi2, RemappedUIsUniform) {
    const Distribution1D d(mixedWeights());
    std::vector<double> counts(1000, 0.0);
    for (int i = 0; i < kSamples; ++i) {
        float r;
        d.sample(uniform(3, i), nullptr, &r);
        ASSERT_TRUE(r >= 0.0f && r < 1.0f) << r;
        counts[std::min(int(r * 1000), 999)] += 1;
    }
    kChi2.expectFits(chi2GoodnessOfFit(counts, std::vector<double>(1000, kSamples / 1000.0)),
                     "pooled remapped u");
}

TEST(Distribution1DChi2, RemappedUIsUniformGivenTheIndex) {
    const std::vector<float> w = mixedWeights();
    kChi2.expectFits(jointChi2(Distribution1D(w), normalized(w), 4, false), "(index, remapped u)");
}

// Negative controls: a pmf 20% off on one entry, and the raw u in place of the remapped one.
TEST(Distribution1DChi2NegativeControl, RejectsAPerturbedPmf) {
    const std::vector<float> w = mixedWeights();
    std::vector<float> wrong = w;
    wrong[1] *= 1.2f;
    kChi2.expectRejects(indexChi2(Distribution1D(w), normalized(wrong), 1), "entry 1 off by 20%");
}

TEST(Distribution1DChi2NegativeControl, RejectsRawUAsRemappedU) {
    const std::vector<float> w = mixedWeights();
    kChi2.expectRejects(jointChi2(Distribution1D(w), normalized(w), 4, true),
                        "raw u given the index");
}

}  // namespace
}  // namespace rr::test

namespace rr::test {
namespace {

// invert() undoes sample(): the remapped coordinate and the index give back u (1-D), and a
// sampled point gives back its u (2-D), which TAIS's preimage-space maps are indexed by.
TEST(DistributionInverse, SampleThenInvertReturnsU) {
    const std::vector<float> weights = {0.5f, 0, 3, 1, 0, 7, 0.25f, 2};
    const Distribution1D d(weights);
    for (int i = 0; i < 20000; ++i) {
        const float u = uniform(40, i);
        float remapped;
        const int index = d.sample(u, nullptr, &remapped);
        EXPECT_NEAR(d.invert(index, remapped), u, 2e-6f) << "u = " << u;
    }
    // 3 × 3 cells with zero cells and a zero row.
    const std::vector<float> grid = {1, 0, 2, 0, 0, 0, 4, 1, 0.5f};
    const Distribution2D d2(grid, 3, 3);
    for (int i = 0; i < 20000; ++i) {
        const Vec2 u = uniform2(41, i);
        float pdf;
        const Vec2 p = d2.sample(u, &pdf);
        const Vec2 back = d2.invert(p);
        EXPECT_NEAR(back.x, u.x, 2e-6f);
        EXPECT_NEAR(back.y, u.y, 2e-6f);
    }
}

}  // namespace
}  // namespace rr::test
