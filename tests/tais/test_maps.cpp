// TAIS mechanics (Cline et al. 2008, §3.3–3.4, Algorithm 1): warping through a map reproduces
// its density (χ²), inversion round-trips, propagation averages neighbours exactly, temporary
// maps splat into the right cells, the 1/n constant keeps every preimage-space density
// strictly positive, samples are credited and the rest of a map's mass is uniform, the scan is
// serpentine, and maximum contribution filtering follows eq. 4.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numeric>
#include <type_traits>
#include <vector>

#include "support/chi2.h"
#include "support/test_random.h"
#include "techniques/tais/contribution_filter.h"
#include "techniques/tais/importance_map.h"
#include "techniques/tais/scan.h"
#include "techniques/tais/temporary_map.h"

namespace rr::test {
namespace {

using tais::InvertedMap1D;
using tais::InvertedMap2D;

// Every χ² run in this file: the 1-D warp without and with a uniform part, discrete draws of
// both parts, the 2-D warp of both parts, and two negative controls.
constexpr int kRuns = 8;
const Chi2Family kChi2(kRuns);
constexpr int kSamples = 1000000;

// Weights with a zero cell, a dominant cell and small ones.
const std::vector<double> kWeights1D = {0.5, 3, 0, 1, 7, 0.25, 2, 1};

// Warped samples of an 8-cell map, histogrammed in 64 bins (8 per cell), against `density`
// per cell (the expected count of a bin is N · density(cell) / 64).
Chi2Outcome warp1DChi2(const InvertedMap1D& map, const std::vector<double>& cellProbability,
                       uint64_t seed) {
    constexpr int kBins = 64;
    std::vector<double> observed(kBins, 0.0), expected(kBins);
    for (int i = 0; i < kSamples; ++i) {
        float pdf;
        const float x = map.warp(uniform(seed, i), &pdf);
        EXPECT_FLOAT_EQ(pdf, map.pdf(x));
        observed[std::min(int(x * kBins), kBins - 1)] += 1;
    }
    const int perCell = kBins / int(cellProbability.size());
    for (int b = 0; b < kBins; ++b)
        expected[b] = kSamples * cellProbability[b / perCell] / perCell;
    return chi2GoodnessOfFit(observed, expected);
}

std::vector<double> probabilities(const std::vector<double>& weights) {
    double total = 0;
    for (double w : weights)
        total += w;
    std::vector<double> p;
    for (double w : weights)
        p.push_back(w / total);
    return p;
}

TEST(InvertedMap1D, WarpedSamplesFollowTheMapDensity) {
    const InvertedMap1D map = InvertedMap1D::fromWeights(kWeights1D);
    kChi2.expectFits(warp1DChi2(map, probabilities(kWeights1D), 1), "1-D warp");
}

// A map's uniform part (the start, the floor, black pixels) adds evenly to every cell's weight.
TEST(InvertedMap1D, TheUniformPartAddsToEveryCell) {
    InvertedMap1D map = InvertedMap1D::fromWeights(kWeights1D);
    map.accumulateUniform(0.5);
    std::vector<double> whole = kWeights1D;
    for (double& w : whole)
        w += 0.5;
    EXPECT_DOUBLE_EQ(map.total(tais::MapPart::Credited), 14.75);
    EXPECT_DOUBLE_EQ(map.total(), 14.75 + 8 * 0.5);
    kChi2.expectFits(warp1DChi2(map, probabilities(whole), 6), "1-D warp with a uniform part");
}

TEST(InvertedMap1D, NegativeControlRejectsTheUniformDensity) {
    const InvertedMap1D map = InvertedMap1D::fromWeights(kWeights1D);
    kChi2.expectRejects(warp1DChi2(map, std::vector<double>(8, 1.0 / 8), 2), "1-D vs uniform");
}

// Discrete draws from a slice of the cells (one path vertex's entries), of the whole map and of
// its credited part alone: each follows its weights, and a cell without credit is never drawn
// from the credited part.
TEST(InvertedMap1D, DiscreteDrawsFromASliceFollowEachPart) {
    InvertedMap1D map = InvertedMap1D::fromWeights(kWeights1D);
    map.accumulateUniform(0.5);
    constexpr int kFirst = 2, kCount = 4;  // credited 0, 1, 7, 0.25
    for (const auto part : {tais::MapPart::Whole, tais::MapPart::Credited}) {
        std::vector<double> observed(kCount, 0.0), expected(kCount);
        for (int i = 0; i < kSamples; ++i)
            observed[size_t(map.sampleCellIn(kFirst, kCount, uniform(3, i), part) - kFirst)] += 1;
        for (int c = 0; c < kCount; ++c)
            expected[size_t(c)] =
                kSamples * map.weight(kFirst + c, part) / map.sliceTotal(kFirst, kCount, part);
        const bool whole = part == tais::MapPart::Whole;
        kChi2.expectFits(chi2GoodnessOfFit(observed, expected),
                         whole ? "discrete slice, whole map" : "discrete slice, credited part");
        if (!whole) {
            EXPECT_EQ(observed[0], 0.0);
        }
    }
}

TEST(InvertedMap1D, WarpAndCdfRoundTrip) {
    const InvertedMap1D map = InvertedMap1D::fromWeights(kWeights1D);
    for (int i = 0; i < 10000; ++i) {
        const float u = uniform(4, i);
        float pdf;
        const float x = map.warp(u, &pdf);
        EXPECT_NEAR(map.cdf(x), u, 2e-6f) << "u = " << u;
        EXPECT_GT(pdf, 0.0f);  // never lands in the zero cell
    }
}

// 4 × 3 cells with a zero row (y = 1) and a zero cell, plus a uniform part of 0.25 per cell:
// warped samples of the whole map, histogrammed 4 × 4 bins per cell, and their density.
struct Histogram2D {
    std::vector<double> counts;
    bool pdfsMatch = true;
};

Histogram2D warp2D(const InvertedMap2D& map, tais::MapPart part, uint64_t seed) {
    constexpr int kX = 16, kY = 12;
    Histogram2D h{std::vector<double>(kX * kY, 0.0)};
    for (int i = 0; i < kSamples; ++i) {
        const Vec2 u = uniform2(seed, i);
        float pdf;
        const Vec2 x = map.warp(u, &pdf, part);
        h.pdfsMatch = h.pdfsMatch && pdf == map.pdf(x, part);
        if (part == tais::MapPart::Whole && i < 10000) {
            const Vec2 back = map.cdf(x);
            EXPECT_NEAR(back.x, u.x, 2e-6f);
            EXPECT_NEAR(back.y, u.y, 2e-6f);
        }
        h.counts[std::min(int(x.y * kY), kY - 1) * kX + std::min(int(x.x * kX), kX - 1)] += 1;
    }
    return h;
}

// Expected counts of warp2D's bins for cell weights `w` (4 × 3).
std::vector<double> expected2D(const std::vector<double>& w) {
    const std::vector<double> p = probabilities(w);
    std::vector<double> expected(16 * 12);
    for (int by = 0; by < 12; ++by)
        for (int bx = 0; bx < 16; ++bx)
            expected[by * 16 + bx] = kSamples * p[(by / 4) * 4 + bx / 4] / 16;
    return expected;
}

// Both parts of a 2-D map: the whole map (the paper's density, credited + uniform) and its
// credited part alone (world maps mixed by evidence), which never lands in a cell without
// credit.
TEST(InvertedMap2D, WarpedSamplesFollowEachPartsDensityAndRoundTrip) {
    const std::vector<double> credited = {1, 2, 0, 3, 0, 0, 0, 0, 5, 1, 1, 0.5};
    InvertedMap2D map = InvertedMap2D::fromWeights(credited, 4, 3);
    map.accumulateUniform(0.25);
    std::vector<double> whole = credited;
    for (double& w : whole)
        w += 0.25;
    const Histogram2D all = warp2D(map, tais::MapPart::Whole, 5);
    EXPECT_TRUE(all.pdfsMatch);
    kChi2.expectFits(chi2GoodnessOfFit(all.counts, expected2D(whole)), "2-D warp");
    kChi2.expectRejects(chi2GoodnessOfFit(all.counts, expected2D(std::vector<double>(12, 1.0))),
                        "2-D vs uniform");
    const Histogram2D part = warp2D(map, tais::MapPart::Credited, 7);
    EXPECT_TRUE(part.pdfsMatch);
    kChi2.expectFits(chi2GoodnessOfFit(part.counts, expected2D(credited)), "2-D credited part");
}

// Fig. 3: the average of seven neighbours' maps is the map of their averaged densities.
TEST(Propagation, AverageOfSevenNeighboursIsTheAverageDensity) {
    std::vector<InvertedMap1D> maps;
    std::vector<double> expected(8, 0.0);
    for (int k = 0; k < 7; ++k) {
        std::vector<double> w(8);
        for (int c = 0; c < 8; ++c)
            w[c] = (k + 1) * (c % 3) + 0.25 * k + (c == k ? 4 : 0);
        maps.push_back(InvertedMap1D::fromWeights(w));
        for (int c = 0; c < 8; ++c)
            expected[c] += w[c] / 7;
    }
    std::vector<const InvertedMap1D*> neighbours;
    for (const auto& m : maps)
        neighbours.push_back(&m);
    const InvertedMap1D average = tais::averageOf<InvertedMap1D>(neighbours);
    for (int c = 0; c < 8; ++c)
        EXPECT_NEAR(average.weight(c), expected[c], 1e-12) << "cell " << c;

    std::vector<InvertedMap2D> maps2;
    std::vector<double> expected2(6, 0.0);
    for (int k = 0; k < 7; ++k) {
        std::vector<double> w(6);
        for (int c = 0; c < 6; ++c)
            w[c] = (c == k % 6 ? 3.0 : 0.5) * (k + 1);
        maps2.push_back(InvertedMap2D::fromWeights(w, 3, 2));
        for (int c = 0; c < 6; ++c)
            expected2[c] += w[c] / 7;
    }
    std::vector<const InvertedMap2D*> neighbours2;
    for (const auto& m : maps2)
        neighbours2.push_back(&m);
    const InvertedMap2D average2 = tais::averageOf<InvertedMap2D>(neighbours2);
    for (int c = 0; c < 6; ++c)
        EXPECT_NEAR(average2.weight(c % 3, c / 3), expected2[c], 1e-12) << "cell " << c;
    EXPECT_NEAR(average2.total(), std::accumulate(expected2.begin(), expected2.end(), 0.0), 1e-12);
}

// Algorithm 1, line 19: continuous maps take |L| into the cell and its neighbours (clipped at
// the map's edges); discrete maps into one entry.
TEST(TemporaryMaps, SplatIntoTheNeighbourhood) {
    tais::TemporaryMap1D line(8);
    line.splat(0.01f, 2.0);  // cell 0: cells 0 and 1
    line.splat(0.5f, 1.0);   // cell 4: cells 3, 4, 5
    line.add(7, 4.0);
    const InvertedMap1D m = line.finish(0);
    const double total = 2 * 2 + 3 * 1 + 4;
    const double expected[8] = {2, 2, 0, 1, 1, 1, 0, 4};
    for (int c = 0; c < 8; ++c)
        EXPECT_NEAR(m.weight(c) / m.total(), expected[c] / total, 1e-12) << "cell " << c;

    tais::TemporaryMap2D square(4, 4);
    square.splat(Vec2(0.99f, 0.3f), 1.0);  // cell (3, 1): x 2..3, y 0..2
    const InvertedMap2D s = square.finish(0);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            EXPECT_NEAR(s.weight(x, y) / s.total(), (x >= 2 && y <= 2) ? 1.0 / 6 : 0.0, 1e-12)
                << x << ", " << y;
}

// Lines 22–23: with 1/n added, every entry keeps at least (1/n) / 2 of the mass however the
// samples fell, so every preimage-space density is at least 1/2: strictly positive, and the
// estimator stays unbiased.
TEST(TemporaryMaps, OneOverNKeepsEveryPreimageDensityPositive) {
    tais::TemporaryMap1D concentrated(64);
    concentrated.add(17, 1e6);
    const InvertedMap1D m = concentrated.finish(tais::preimageFloor(64));
    for (int c = 0; c < 64; ++c)
        EXPECT_GE(m.pdf((c + 0.5f) / 64), 0.5f - 1e-6f) << "cell " << c;
    EXPECT_NEAR(m.pdf(17.5f / 64), 64 * (1.0 + 1.0 / 64) / 2, 1e-4);

    tais::TemporaryMap2D square(32, 32);
    square.splat(Vec2(0.5f, 0.5f), 3.0);
    const InvertedMap2D s = square.finish(tais::preimageFloor(32 * 32));
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x)
            EXPECT_GE(s.pdf(Vec2((x + 0.5f) / 32, (y + 0.5f) / 32)), 0.5f - 1e-5f);

    // A map that received nothing is uniform.
    const InvertedMap1D empty = tais::TemporaryMap1D(16).finish(tais::preimageFloor(16));
    for (int c = 0; c < 16; ++c)
        EXPECT_NEAR(empty.pdf((c + 0.5f) / 16), 1.0f, 1e-6f);
}

// The two parts of a pixel's maps through Algorithm 1: uniform maps have no credited mass; a
// finished temporary map adds its samples' normalised weights as credited mass and the
// constant of line 23 as uniform mass; an empty one (a black pixel) adds uniform mass only;
// normalising keeps the parts' ratio.
TEST(TemporaryMaps, SamplesAreCreditedTheConstantAndBlackPixelsAreUniform) {
    tais::TemporaryMap1D pixel(16);
    pixel.add(0, 3.0);
    pixel.add(1, 1.0);
    InvertedMap1D map(16);
    map.normalize();
    EXPECT_EQ(map.total(tais::MapPart::Credited), 0.0);
    const double f = 1e-3 / 16, norm = 1 / (1 + 16 * f);  // floor per entry, line 23
    pixel.addFinishedTo(map, f);
    EXPECT_NEAR(map.total(tais::MapPart::Credited), norm, 1e-15);
    EXPECT_NEAR(map.weight(0, tais::MapPart::Credited), 0.75 * norm, 1e-15);
    EXPECT_NEAR(map.total(), 2, 1e-15);
    tais::TemporaryMap1D(16).addFinishedTo(map, f);  // a black pixel
    EXPECT_NEAR(map.total(tais::MapPart::Credited), norm, 1e-15);
    map.normalize();
    EXPECT_NEAR(map.total(tais::MapPart::Credited), norm / 3, 1e-15);
    EXPECT_NEAR(map.weight(5), (2.0 / 16 + f * norm) / 3, 1e-15);  // uniform only

    tais::TemporaryMap2D square(4, 4);
    square.splat(Vec2(0.1f, 0.1f), 2.0);
    InvertedMap2D map2(4, 4);
    map2.normalize();
    square.addFinishedTo(map2, f);
    EXPECT_NEAR(map2.total(tais::MapPart::Credited), 1 / (1 + 16 * f), 1e-15);
    EXPECT_EQ(map2.weight(3, 3, tais::MapPart::Credited), 0.0);
}

// assignSum and slide, the one-pass forms the scan uses, give the bits of the operations they
// replace: a copy, an accumulate() per further part and a normalize(); accumulate(+1), then
// accumulate(−1). (Equal bits keep TAIS's renders identical to the multi-pass code's.) One to
// five parts: every loop assignSum has.
TEST(Maps, OnePassSumsAndSlidesGiveTheBitsOfTheirSteps) {
    auto map1 = [](int seed) {
        std::vector<double> w(7);
        for (size_t i = 0; i < w.size(); ++i)
            w[i] = std::fmod(0.37 * double(i * i + 3 * seed) + 0.11 * seed, 1.3);
        InvertedMap1D m = InvertedMap1D::fromWeights(w);
        m.accumulateUniform(0.01 * seed);
        return m;
    };
    auto map2 = [](int seed) {
        std::vector<double> w(5 * 3);
        for (size_t i = 0; i < w.size(); ++i)
            w[i] = std::fmod(0.29 * double(i * i + 5 * seed) + 0.07 * seed, 0.9);
        InvertedMap2D m = InvertedMap2D::fromWeights(w, 5, 3);
        m.accumulateUniform(0.02 * seed);
        return m;
    };
    auto expectSameBits = [](const auto& a, const auto& b, const char* what) {
        const auto cells = [](const auto& m) {
            std::vector<double> out;
            if constexpr (std::is_same_v<std::decay_t<decltype(m)>, InvertedMap1D>) {
                for (int c = 0; c < m.cells(); ++c)
                    out.push_back(m.weight(c));
            } else {
                for (int y = 0; y < m.height(); ++y)
                    for (int x = 0; x < m.width(); ++x)
                        out.push_back(m.weight(x, y));
            }
            out.push_back(m.total());
            return out;
        };
        EXPECT_EQ(cells(a), cells(b)) << what;
    };
    auto check = [&](auto make, const char* what) {
        const auto p0 = make(1), p1 = make(2), p2 = make(3), p3 = make(4), p4 = make(5);
        const std::array parts = {&p0, &p1, &p2, &p3, &p4};
        for (size_t count = 1; count <= parts.size(); ++count)  // each loop of assignSum
            for (bool normalize : {false, true}) {
                auto steps = p0;
                for (size_t k = 1; k < count; ++k)
                    steps.accumulate(*parts[k]);
                if (normalize) steps.normalize();
                auto fused = make(9);  // any prior content is overwritten
                fused.assignSum(std::span(parts.data(), count), normalize);
                expectSameBits(fused, steps, what);
            }
        auto steps = p0;
        steps.accumulate(p1);
        steps.accumulate(p2, -1);
        auto slid = p0;
        slid.slide(&p1, &p2);
        expectSameBits(slid, steps, what);
        auto one = p0;
        one.slide(nullptr, &p2);
        auto oneSteps = p0;
        oneSteps.accumulate(p2, -1);
        expectSameBits(one, oneSteps, what);
    };
    check(map1, "1-D");
    check(map2, "2-D");
}

// Fig. 3 as we read it, the definition MapRows is checked against: x−2 … x+2 in the row above
// and the two previous pixels of this row in its scan direction (even rows run left to right),
// clipped at the edges; none for the band's first pixel.
struct Pixel {
    int x, y;
};
std::vector<Pixel> renderedNeighbours(int x, int row, int width) {
    std::vector<Pixel> neighbours;
    if (row > 0)
        for (int dx = -2; dx <= 2; ++dx)
            if (x + dx >= 0 && x + dx < width) neighbours.push_back({x + dx, row - 1});
    const int back = row % 2 == 0 ? -1 : 1;
    for (int k = 1; k <= 2; ++k)
        if (x + back * k >= 0 && x + back * k < width) neighbours.push_back({x + back * k, row});
    return neighbours;
}

// Propagation through two stored rows: each pixel of a serpentine scan starts from the sum of
// its rendered neighbours' maps, the five above kept as a running sum along the row (and
// summed afresh after a jump), equal to the direct sum.
TEST(Scan, MapRowsSumTheRenderedNeighbours) {
    constexpr int kWidth = 9, kRows = 4;
    auto mapOf = [](int x, int y) {
        std::vector<double> w = {1e-3, 1, 0, 1};
        w[size_t((x + y) % 4)] += 10.0 * (x + 1) + y;
        InvertedMap1D map = InvertedMap1D::fromWeights(w);
        map.accumulateUniform(0.1 * y);
        return map;
    };
    tais::MapRows<InvertedMap1D> rows(kWidth, InvertedMap1D(4));
    InvertedMap1D start(4);
    // The neighbours' sum (the only form the renderer uses it in is normalised).
    auto neighbourSum = [&rows](int x, int y, InvertedMap1D* out) {
        const auto n = rows.neighbours(x, y);
        out->assignSum(n.list(), false);
        return n.count;
    };
    EXPECT_EQ(neighbourSum(0, 0, &start), 1);  // no neighbour: the initial map
    EXPECT_NEAR(start.weight(2) / start.total(), 0.25, 1e-12);
    for (int y = 0; y < kRows; ++y) {
        if (y > 0) rows.nextRow();
        for (int i = 0; i < kWidth; ++i) {
            const int x = y % 2 == 0 ? i : kWidth - 1 - i;
            if (y == 2 && i == 4) {  // a call out of order: the window is summed afresh
                InvertedMap1D other(4);
                neighbourSum(0, y, &other);
            }
            const std::vector<Pixel> expected = renderedNeighbours(x, y, kWidth);
            const int count = neighbourSum(x, y, &start);
            EXPECT_EQ(count, std::max<int>(int(expected.size()), 1)) << x << ", " << y;
            for (int c = 0; c < 4 && !expected.empty(); ++c) {
                double sum = 0;
                for (const Pixel& n : expected)
                    sum += mapOf(n.x, n.y).weight(c);
                EXPECT_NEAR(start.weight(c), sum, 1e-12 * sum) << x << ", " << y << ", cell " << c;
            }
            InvertedMap1D m = mapOf(x, y);
            rows.store(x, &m);
        }
    }
}

// Eq. (4) by hand. With n = 4 samples the factor is max(32/4, 0.02) = 8: a sample is clamped
// only if it is brighter than 8 times the others together. With n = 2000 the factor is 0.02.
TEST(ContributionFilter, ClampsToEquationFour) {
    std::vector<Rgb> few = {Rgb(1.0f), Rgb(1.0f), Rgb(1.0f), Rgb(100.0f)};
    EXPECT_EQ(tais::filterMaximumContribution(few), 1);
    EXPECT_NEAR(few[3].luminance(), 3 * 8.0f, 1e-4f);  // (s − s_i) · 8 = 3 · 8
    EXPECT_FLOAT_EQ(few[0].g, 1.0f);

    std::vector<Rgb> many(2000, Rgb(0.5f, 1.0f, 2.0f));
    const float unit = many[0].luminance();
    many[7] = Rgb(0.5f, 1.0f, 2.0f) * 100.0f;  // brighter than 0.02 × the other 1999
    EXPECT_EQ(tais::filterMaximumContribution(many), 1);
    EXPECT_NEAR(many[7].luminance(), 1999 * unit * 0.02f, 1e-3f);
    EXPECT_NEAR(many[7].b / many[7].r, 4.0f, 1e-5f);  // the colour keeps its hue

    std::vector<Rgb> even(16, Rgb(0.3f));
    EXPECT_EQ(tais::filterMaximumContribution(even), 0);
}

}  // namespace
}  // namespace rr::test
