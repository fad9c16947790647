// The shared χ² tooling itself: the statistic, pooling and p-value against hand-computed
// values, Šidák levels, and the histograms' cell layout and numerical integration.
#include <gtest/gtest.h>

#include <cmath>

#include "support/chi2.h"
#include "support/histograms.h"

namespace rr::test {
namespace {

TEST(Chi2, StatisticDegreesOfFreedomAndPValueByHand) {
    // (12−10)²/10 + (8−10)²/10 + (20−20)²/20 = 0.8 with 2 degrees of freedom: p = e^(−0.4).
    const Chi2Outcome r = chi2GoodnessOfFit({12, 8, 20}, {10, 10, 20});
    EXPECT_DOUBLE_EQ(r.statistic, 0.8);
    EXPECT_EQ(r.degreesOfFreedom, 2);
    EXPECT_NEAR(r.pValue, std::exp(-0.4), 1e-12);
    EXPECT_TRUE(r.failure.empty());
}

TEST(Chi2, CellsBelowFiveArePooled) {
    // Cells expecting 2 and 3 are pooled into one expecting 5 (observed 1 + 6 = 7):
    // (7−5)²/5 + (10−10)²/10 = 0.8, two cells, one degree of freedom.
    const Chi2Outcome r = chi2GoodnessOfFit({1, 6, 10}, {2, 3, 10});
    EXPECT_EQ(r.pooledCells, 2);
    EXPECT_EQ(r.degreesOfFreedom, 1);
    EXPECT_DOUBLE_EQ(r.statistic, 0.8);
}

TEST(Chi2, SamplesWhereTheDensityIsZeroFail) {
    const Chi2Outcome r = chi2GoodnessOfFit({5, 1}, {6, 0});
    EXPECT_FALSE(r.failure.empty());
    EXPECT_FALSE(r.passes(0.01));
}

TEST(Chi2, SidakAndZThresholds) {
    EXPECT_NEAR(sidakAlpha(0.01, 1), 0.01, 1e-15);
    EXPECT_NEAR(1 - std::pow(1 - sidakAlpha(0.01, 20), 20), 0.01, 1e-12);
    EXPECT_NEAR(zThreshold(0.05), 1.959963984540054, 1e-9);
}

TEST(DirectionHistogram, CellLayoutAndUniformExpectation) {
    DirectionHistogram h(7, 9, -0.4);
    for (int iz = 0; iz < 7; ++iz)
        for (int ip = 0; ip < 9; ++ip)
            h.add(h.direction(iz + 0.5, ip + 0.5));
    for (int i = 0; i < 63; ++i)
        EXPECT_EQ(h.counts()[i], 1.0) << i;
    EXPECT_EQ(h.counts()[63], 0.0);
    h.add(Vec3(0, 0, -1));  // below the band
    EXPECT_EQ(h.counts()[63], 1.0);
    // The uniform density puts 1.4/2 of its mass in the band z ∈ [−0.4, 1], equally per cell.
    const auto expected = h.expected([](const Vec3&) { return 1 / (4 * M_PI); }, 630.0);
    for (int i = 0; i < 63; ++i)
        EXPECT_NEAR(expected[i], 630.0 * 0.7 / 63, 1e-9);
}

// A spherical cap whose edge crosses cells: no cell holding part of the cap expects zero, and
// the total mass is within the midpoint rule's bound for a step on the refined grid: the edge
// runs along one row of cells, so at most half a sub-row (dz / 96 / 2) of the full circle of
// azimuth is misassigned.
TEST(DirectionHistogram, EdgeCellsOfADiscontinuousDensityAreIntegratedAccurately) {
    const double capOneMinusCos = 0.37;  // edge at z = 0.63: inside a cell of 17
    const auto cap = [&](const Vec3& w) {
        return w.z >= 1 - capOneMinusCos ? 1 / (2 * M_PI * capOneMinusCos) : 0.0;
    };
    const DirectionHistogram h(17, 24, 0.0);
    const auto expected = h.expected(cap, 1.0);
    double total = 0;
    for (double e : expected)
        total += e;
    const double density = 1 / (2 * M_PI * capOneMinusCos);
    const double bound = (1.0 / 17) / 96 / 2 * 2 * M_PI * density;
    EXPECT_NEAR(total, 1.0, bound);
    EXPECT_LT(bound, 1e-3);  // far below what a χ² test on 10⁶ samples can notice
    // The row holding the edge (z ∈ [10/17, 11/17)) has positive expectation in every cell.
    for (int ip = 0; ip < 24; ++ip)
        EXPECT_GT(expected[10 * 24 + ip], 0.0);
}

TEST(PlaneHistogram, DiskAreaIsIntegratedAccurately) {
    const PlaneHistogram h(15, 15, -1, 1, -1, 1);
    const auto expected =
        h.expected([](const Vec2& p) { return p.x * p.x + p.y * p.y <= 1 ? 1 / M_PI : 0.0; }, 1.0);
    double total = 0;
    for (double e : expected)
        total += e;
    // The circle crosses about 2·15·2 edge cells, each misassigning at most half a sub-cell
    // strip of width (2/15)/96 along a cell side of length 2/15, at density 1/π.
    const double bound = 60 * 0.5 * (2.0 / 15) / 96 * (2.0 / 15) / M_PI;
    EXPECT_NEAR(total, 1.0, bound);
}

}  // namespace
}  // namespace rr::test
