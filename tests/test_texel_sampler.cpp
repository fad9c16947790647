// Tests of TexelSampler (sampling/texel_sampler.h), the environment map's two-level texel
// sampler: its density is the weights', normalised, and the probability with which it selects
// each texel (χ² over texels, with negative controls); points are uniform inside their texel;
// it carries each texel's value; invert() undoes sample(); and maps whose sides are not
// multiples of the block (ragged last blocks), zero texels and zero rows.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "sampling/texel_sampler.h"
#include "support/chi2.h"
#include "support/test_random.h"

namespace rr::test {
namespace {

// χ² runs in this file: texels of 2 maps, sub-texel position, 2 negative controls.
constexpr int kRuns = 5;
const Chi2Family kChi2(kRuns);
constexpr int kSamples = 1000000;

struct Map {
    int width, height;
    std::vector<float> weights;
    std::vector<Rgb> values;
};

// 21 × 13 texels (ragged blocks on both sides) of weights spanning four orders of magnitude,
// with a zero texel every seventh and a zero row.
Map raggedMap() {
    Map m{21, 13, {}, {}};
    for (int i = 0; i < m.width * m.height; ++i) {
        const bool zero = i % 7 == 3 || i / m.width == 5;
        m.weights.push_back(zero ? 0.0f : std::pow(10.0f, 4.0f * uniform(3, uint64_t(i)) - 2.0f));
        m.values.push_back(Rgb(float(i), float(i % 5), 1.0f));
    }
    return m;
}

// 64 × 32 texels, one bright 3 × 2 patch on a dim background (a sun).
Map sunMap() {
    Map m{64, 32, {}, {}};
    for (int i = 0; i < m.width * m.height; ++i) {
        const int x = i % m.width, y = i / m.width;
        const bool sun = x >= 40 && x < 43 && y >= 7 && y < 9;
        m.weights.push_back(sun ? 5000.0f : 1.0f);
        m.values.push_back(Rgb(float(i)));
    }
    return m;
}

// The probability of each texel: its weight over the total.
std::vector<double> texelProbabilities(const Map& m) {
    const double total = std::accumulate(m.weights.begin(), m.weights.end(), 0.0);
    std::vector<double> p;
    for (float w : m.weights)
        p.push_back(double(w) / total);
    return p;
}

Chi2Outcome texelChi2(const TexelSampler& s, const std::vector<double>& p, uint64_t seed) {
    std::vector<double> counts(p.size(), 0.0), expected(p.size());
    for (int i = 0; i < kSamples; ++i) {
        TexelSampler::Draw d;
        if (s.sample(uniform2(seed, uint64_t(i)), &d))
            counts[size_t(d.row) * s.width() + size_t(d.column)] += 1;
    }
    for (size_t i = 0; i < p.size(); ++i)
        expected[i] = p[i] * kSamples;
    return chi2GoodnessOfFit(counts, expected);
}

// Each texel's probability is the product of four interval widths (its row of blocks, block,
// row in the block, texel in the row), three of them from float CDFs, each width within 2⁻²³ of
// the exact one: a texel's probability is within 3·2⁻²³ of its row of blocks' (8 image rows)
// probability of the exact one, and they sum to 1.
TEST(TexelSampler, DensityIsTheNormalisedWeightPerUnitArea) {
    for (const Map& m : {raggedMap(), sunMap()}) {
        const TexelSampler s(m.weights, m.values, m.width, m.height);
        const std::vector<double> p = texelProbabilities(m);
        std::vector<double> band((size_t(m.height) + 7) / 8, 0.0);
        for (size_t i = 0; i < p.size(); ++i)
            band[i / size_t(m.width) / 8] += p[i];
        const double cells = double(m.width) * m.height;
        double sum = 0;
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x) {
                const double density = s.density(x, y), expected = p[size_t(y) * m.width + x];
                sum += density / cells;
                if (expected == 0) {
                    EXPECT_EQ(density, 0) << x << ", " << y;
                } else {
                    EXPECT_NEAR(density / cells, expected, 3 * 0x1p-23 * band[size_t(y) / 8])
                        << x << ", " << y;
                }
            }
        EXPECT_NEAR(sum, 1.0, 1e-5);
    }
}

TEST(TexelSampler, DrawsCarryTheirTexelsValueAndDensityAndLieInIt) {
    const Map m = raggedMap();
    const TexelSampler s(m.weights, m.values, m.width, m.height);
    for (int i = 0; i < 100000; ++i) {
        TexelSampler::Draw d;
        ASSERT_TRUE(s.sample(uniform2(5, uint64_t(i)), &d));
        const size_t texel = size_t(d.row) * m.width + size_t(d.column);
        ASSERT_GT(m.weights[texel], 0.0f) << "a zero texel was drawn";
        EXPECT_EQ(d.value, m.values[texel]);
        EXPECT_EQ(d.density, s.density(d.column, d.row));
        EXPECT_EQ(int(d.point.x * float(m.width)), d.column);
        EXPECT_EQ(int(d.point.y * float(m.height)), d.row);
    }
}

TEST(TexelSampler, InvertUndoesSample) {
    for (const Map& m : {raggedMap(), sunMap()}) {
        const TexelSampler s(m.weights, m.values, m.width, m.height);
        for (int i = 0; i < 100000; ++i) {
            const Vec2 u = uniform2(7, uint64_t(i));
            TexelSampler::Draw d;
            ASSERT_TRUE(s.sample(u, &d));
            const Vec2 back = s.invert(d.point);
            EXPECT_NEAR(back.x, u.x, 4e-6f) << u.x << ", " << u.y;
            EXPECT_NEAR(back.y, u.y, 4e-6f) << u.x << ", " << u.y;
        }
    }
}

TEST(TexelSampler, AllZeroWeightsAreUniform) {
    const Map m{10, 9, std::vector<float>(90, 0.0f), std::vector<Rgb>(90, Rgb(1.0f))};
    const TexelSampler s(m.weights, m.values, m.width, m.height);
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x)
            EXPECT_NEAR(s.density(x, y), 1.0f, 1e-5f);
}

TEST(TexelSamplerChi2, TexelsFollowTheWeights) {
    for (const Map& m : {raggedMap(), sunMap()}) {
        const TexelSampler s(m.weights, m.values, m.width, m.height);
        kChi2.expectFits(texelChi2(s, texelProbabilities(m), 11),
                         std::to_string(m.width) + "x" + std::to_string(m.height));
    }
}

// The position inside the texel, pooled over texels in 4 × 4 sub-cells: uniform.
TEST(TexelSamplerChi2, PointsAreUniformInsideTheirTexel) {
    const Map m = raggedMap();
    const TexelSampler s(m.weights, m.values, m.width, m.height);
    std::vector<double> counts(16, 0.0), expected(16, double(kSamples) / 16);
    for (int i = 0; i < kSamples; ++i) {
        TexelSampler::Draw d;
        ASSERT_TRUE(s.sample(uniform2(13, uint64_t(i)), &d));
        const float fx = d.point.x * float(m.width) - float(d.column);
        const float fy = d.point.y * float(m.height) - float(d.row);
        counts[size_t(std::min(int(fy * 4), 3) * 4 + std::min(int(fx * 4), 3))] += 1;
    }
    kChi2.expectFits(chi2GoodnessOfFit(counts, expected));
}

// Negative controls: uniform texels, and the sun's weight taken as 10 % lower, are rejected.
TEST(TexelSamplerChi2, WrongDensitiesAreRejected) {
    const Map m = sunMap();
    const TexelSampler s(m.weights, m.values, m.width, m.height);
    kChi2.expectRejects(
        texelChi2(s, std::vector<double>(m.weights.size(), 1.0 / m.weights.size()), 17), "uniform");
    Map dimmer = m;
    for (float& w : dimmer.weights)
        if (w > 1) w *= 0.9f;
    kChi2.expectRejects(texelChi2(s, texelProbabilities(dimmer), 17), "sun 10 % dimmer");
}

}  // namespace
}  // namespace rr::test
