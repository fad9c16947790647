// Tests of the sample generators (sampling/sampler.h) and their building blocks in
// sampling/hash.h: determinism, range, uniformity (χ²), stratification of the structured
// samplers (modulo their Cranley–Patterson rotation), repeats, and independence of decisions.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <vector>

#include "loader/factories.h"
#include "sampling/hash.h"
#include "sampling/sampler.h"
#include "support/chi2.h"
#include "support/histograms.h"

namespace rr::test {
namespace {

// Every χ² run in this file: 5 per sampler type (every-index 1-D and 2-D, fixed-index 1-D and
// 2-D, repeats) × 4 types, and 2 negative controls.
constexpr int kRuns = 22;
const Chi2Family kChi2(kRuns);
const double kAlpha = kChi2.alpha();
// Every correlation z-test in this file: 5 pairs × 4 types, and 1 negative control.
constexpr int kZTests = 21;
const double kZ = zThreshold(sidakAlpha(0.01, kZTests));

constexpr SamplerType kAllTypes[] = {SamplerType::Independent, SamplerType::Stratified,
                                     SamplerType::Hammersley, SamplerType::PbrtV1};
constexpr SamplerType kStructuredTypes[] = {SamplerType::Stratified, SamplerType::Hammersley,
                                            SamplerType::PbrtV1};

// A parameterised suite over the three sampler types, named after them.
class EachSampler : public ::testing::TestWithParam<SamplerType> {
  protected:
    SamplerType type() const { return GetParam(); }
    std::string name() const { return samplerName(GetParam()); }
};
auto typeName = [](const ::testing::TestParamInfo<SamplerType>& info) {
    return std::string(samplerName(info.param));
};

class EachStructuredSampler : public EachSampler {};

// 1-D histogram of values in [0, 1) against the uniform density.
class UnitHistogram {
  public:
    explicit UnitHistogram(int cells) : counts_(size_t(cells) + 1, 0.0) {}
    void add(float x) {
        if (!(x >= 0.0f && x < 1.0f)) {
            counts_.back() += 1;  // outside [0, 1): expects nothing
            return;
        }
        const int cells = int(counts_.size()) - 1;
        counts_[std::min(int(double(x) * cells), cells - 1)] += 1;
    }
    Chi2Outcome test(double samples) const {
        std::vector<double> expected(counts_.size(), samples / double(counts_.size() - 1));
        expected.back() = 0;
        return chi2GoodnessOfFit(counts_, expected);
    }

  private:
    std::vector<double> counts_;
};

Chi2Outcome planeUniformChi2(const PlaneHistogram& h, double samples) {
    return chi2GoodnessOfFit(h.counts(), h.expected([](const Vec2&) { return 1.0; }, samples));
}

// Columns of the 2-D strata grid the sampler uses for n strata: the largest divisor of n not
// above √n (sampler.h: gridColumns × (setSize / gridColumns)).
uint32_t gridColumns(uint32_t n) {
    uint32_t c = 1;
    for (uint32_t d = 1; d * d <= n; ++d)
        if (n % d == 0) c = d;
    return c;
}

double frac(double x) {
    return x - std::floor(x);
}

// True when the values fall one per stratum [o + k/n, o + (k+1)/n) (mod 1) for some offset o:
// with the sorted values x_(i), this holds exactly when all n·x_(i) − i lie in an interval
// of length < 1. Returns the spread max − min of n·x_(i) − i.
double shiftedStrataSpread(std::vector<float> xs) {
    std::sort(xs.begin(), xs.end());
    const double n = double(xs.size());
    double lo = 1e9, hi = -1e9;
    for (size_t i = 0; i < xs.size(); ++i) {
        const double u = n * xs[i] - double(i);
        lo = std::min(lo, u);
        hi = std::max(hi, u);
    }
    return hi - lo;
}
bool oneInEachShiftedStratum(const std::vector<float>& xs) {
    return shiftedStrataSpread(xs) < 1.0;
}

// Cell of each value among `cells` equal strata shifted so that `origin` starts a stratum.
std::vector<int> shiftedCells(const std::vector<float>& xs, double origin, int cells) {
    std::vector<int> out(xs.size());
    for (size_t i = 0; i < xs.size(); ++i)
        out[i] = std::min(int(frac(double(xs[i]) - origin) * cells), cells - 1);
    return out;
}

// The distinct assignments of values to `cells` shifted strata with exactly `perCell` values
// in each. A valid offset can always be moved up to a sample value (the assignment only
// changes when a stratum boundary crosses a value), so the values are the only candidates.
// Assignments are relabelled so that value 0 is in stratum 0 (a cyclic relabelling does not
// change which values share a stratum).
std::set<std::vector<int>> balancedShifts(const std::vector<float>& xs, int cells, int perCell) {
    std::set<std::vector<int>> out;
    for (float origin : xs) {
        std::vector<int> c = shiftedCells(xs, origin, cells);
        std::vector<int> count(cells, 0);
        for (int v : c)
            ++count[v];
        if (std::any_of(count.begin(), count.end(), [&](int k) { return k != perCell; })) continue;
        const int first = c[0];
        for (int& v : c)
            v = (v - first + cells) % cells;
        out.insert(c);
    }
    return out;
}

// True when the points fall one per cell of a cols × rows grid shifted toroidally by some
// (ox, oy).
bool oneInEachShiftedCell(const std::vector<Vec2>& ps, int cols, int rows) {
    std::vector<float> xs, ys;
    for (const Vec2& p : ps) {
        xs.push_back(p.x);
        ys.push_back(p.y);
    }
    const auto columns = balancedShifts(xs, cols, rows);
    const auto rowSets = balancedShifts(ys, rows, cols);
    for (const auto& cx : columns)
        for (const auto& cy : rowSets) {
            std::vector<bool> used(size_t(cols) * rows, false);
            bool ok = true;
            for (size_t i = 0; i < ps.size() && ok; ++i) {
                const size_t cell = size_t(cy[i]) * cols + cx[i];
                ok = !used[cell];
                used[cell] = true;
            }
            if (ok) return true;
        }
    return false;
}

// For n = 2^m points of a Cranley–Patterson-rotated Hammersley set: both coordinates are
// lattices {o + k/n}, and every family of elementary intervals 2^-p × 2^-(m-p), shifted
// toroidally by the rotation, holds exactly one point. Returns an empty string on success.
std::string hammersleyNetDefect(const std::vector<Vec2>& ps) {
    const uint32_t n = uint32_t(ps.size());
    int m = 0;
    while ((1u << m) < n)
        ++m;
    if ((1u << m) != n) return "not a power of two";
    std::vector<uint32_t> kx(n), ky(n);
    std::vector<bool> seenX(n, false), seenY(n, false);
    for (uint32_t i = 0; i < n; ++i) {
        const double ux = frac(double(ps[i].x) - ps[0].x) * n;
        const double uy = frac(double(ps[i].y) - ps[0].y) * n;
        if (std::abs(ux - std::round(ux)) > 1e-3 || std::abs(uy - std::round(uy)) > 1e-3)
            return "point " + std::to_string(i) + " is off the lattice";
        kx[i] = uint32_t(std::llround(ux)) % n;
        ky[i] = uint32_t(std::llround(uy)) % n;
        if (seenX[kx[i]] || seenY[ky[i]]) return "two points share a lattice line";
        seenX[kx[i]] = seenY[ky[i]] = true;
    }
    // With 2^p columns any cyclic shift of the x lattice works (2^(m-p) consecutive indices
    // cover every residue of the low bits); the y shift is searched.
    for (int p = 0; p <= m; ++p) {
        bool found = false;
        for (uint32_t d = 0; d < (1u << p) && !found; ++d) {
            std::vector<bool> used(n, false);
            bool ok = true;
            for (uint32_t i = 0; i < n && ok; ++i) {
                const uint32_t cx = kx[i] >> (m - p);
                const uint32_t cy = ((ky[i] + n - d) % n) >> p;
                const uint32_t cell = cy * (1u << p) + cx;
                ok = !used[cell];
                used[cell] = true;
            }
            found = ok;
        }
        if (!found)
            return "no shifted 2^-" + std::to_string(p) + " x 2^-" + std::to_string(m - p) +
                   " elementary intervals with one point each";
    }
    return "";
}

// --- Hash building blocks ---------------------------------------------------------------------

TEST(PermuteIndex, IsABijectionForManySizesAndKeys) {
    std::vector<uint32_t> sizes;
    for (uint32_t n = 1; n <= 300; ++n)
        sizes.push_back(n);
    for (uint32_t n : {511u, 512u, 513u, 1000u, 4096u, 4097u, 65535u, 65537u})
        sizes.push_back(n);
    for (uint32_t n : sizes) {
        const int keys = n <= 300 ? 24 : 4;
        for (int k = 0; k < keys; ++k) {
            const uint32_t key = pcgOutput(hashKeys(1234, n, k));
            std::vector<bool> seen(n, false);
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t j = permuteIndex(i, n, key);
                ASSERT_LT(j, n) << "n = " << n << ", key = " << key << ", i = " << i;
                ASSERT_FALSE(seen[j])
                    << "n = " << n << ", key = " << key << ": " << j << " hit twice";
                seen[j] = true;
            }
        }
    }
    // One large size, one key.
    const uint32_t n = 1000003;
    std::vector<bool> seen(n, false);
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t j = permuteIndex(i, n, 0x9e3779b9u);
        ASSERT_LT(j, n);
        ASSERT_FALSE(seen[j]) << j << " hit twice";
        seen[j] = true;
    }
}

TEST(PermuteIndex, DifferentKeysGiveDifferentPermutations) {
    const uint32_t n = 64;
    std::set<std::vector<uint32_t>> perms;
    for (uint32_t k = 0; k < 100; ++k) {
        std::vector<uint32_t> p(n);
        for (uint32_t i = 0; i < n; ++i)
            p[i] = permuteIndex(i, n, pcgOutput(hashKeys(9, k)));
        perms.insert(p);
    }
    EXPECT_EQ(perms.size(), 100u);
}

TEST(RadicalInverse, KnownValues) {
    EXPECT_EQ(radicalInverseBase2(0), 0.0f);
    EXPECT_EQ(radicalInverseBase2(1), 0.5f);
    EXPECT_EQ(radicalInverseBase2(2), 0.25f);
    EXPECT_EQ(radicalInverseBase2(3), 0.75f);
    EXPECT_EQ(radicalInverseBase2(4), 0.125f);
    EXPECT_EQ(radicalInverseBase2(5), 0.625f);
    EXPECT_EQ(radicalInverseBase2(6), 0.375f);
    EXPECT_EQ(radicalInverseBase2(7), 0.875f);
    EXPECT_EQ(radicalInverseBase2(0x80000000u), 0.0f);  // 2^-32: below the 24 kept bits
    EXPECT_EQ(radicalInverseBase2(0x00000100u), 0x1p-9f);
    EXPECT_EQ(radicalInverseBase2(0xffffffffu), 1.0f - 0x1p-24f);
    // Against the definition Σ b_k 2^-(k+1), truncated to 24 bits.
    for (int t = 0; t < 2000; ++t) {
        const uint32_t i = pcgOutput(hashKeys(77, t));
        double v = 0;
        for (int k = 0; k < 24; ++k)
            if (i & (1u << k)) v += std::ldexp(1.0, -(k + 1));
        ASSERT_EQ(double(radicalInverseBase2(i)), v) << "i = " << i;
    }
}

TEST(UnitFloat, CoversZeroToJustBelowOne) {
    EXPECT_EQ(toUnitFloat(0), 0.0f);
    EXPECT_EQ(toUnitFloat(0xffffffffu), 1.0f - 0x1p-24f);
    EXPECT_LT(toUnitFloat(0xffffffffu), 1.0f);
}

// --- Determinism and distinct streams ----------------------------------------------------------

const DecisionSite kSites[] = {
    {Decision::FilmPosition},
    {Decision::Time},
    {Decision::Lens},
    {Decision::LightSelect},
    {Decision::LightPoint},
    {Decision::BsdfLobe},
    {Decision::BsdfDirection},
    {Decision::MediumDistance},
    {Decision::RussianRoulette},
    {Decision::BsdfDirection, 1},
    {Decision::BsdfDirection, 7},
    {Decision::LightPoint, 2, 1, 3},
};

// A decision's id is hashed into every coordinate it draws: the standard decisions and those the
// techniques register keep the ids (and dimensions) every image so far was made with, and no two
// share an id or a name.
TEST(Decisions, KeepTheirIdsAndShareNone) {
    // By id.
    const std::vector<std::string> names = {"film_position",
                                            "time",
                                            "lens",
                                            "light_select",
                                            "light_point",
                                            "bsdf_lobe",
                                            "bsdf_direction",
                                            "medium_distance",
                                            "russian_roulette",
                                            "resample_count",
                                            "resample_select",
                                            "candidate_lobe",
                                            "candidate_direction",
                                            "peak_lobe",
                                            "peak_direction",
                                            "mixture_count",
                                            "mixture_lobe",
                                            "mixture_direction"};
    const std::vector<int> dimensions = {2, 1, 2, 1, 2, 1, 2, 1, 1, 1, 1, 1, 2, 1, 2, 1, 1, 2};
    std::vector<std::string> registeredNames(names.size());
    std::vector<int> registeredDimensions(names.size());
    for (const Decision& d : techniqueRegistry().decisions()) {
        ASSERT_LT(d.id, names.size()) << d.name;
        EXPECT_TRUE(registeredNames[d.id].empty()) << d.name << " shares id " << int(d.id);
        registeredNames[d.id] = d.name;
        registeredDimensions[d.id] = d.dimensions;
    }
    EXPECT_EQ(registeredNames, names);
    EXPECT_EQ(registeredDimensions, dimensions);

    // Negative controls: a technique's decision may take neither a standard id nor a name.
    TechniqueRegistry registry;
    EXPECT_THROW(registry.addDecisions(std::array{Decision{Decision::Time.id, 1, "my_time"}}),
                 std::logic_error);
    EXPECT_THROW(registry.addDecisions(std::array{Decision{200, 1, "time"}}), std::logic_error);
}

TEST_P(EachSampler, SameCoordinatesGiveTheSameValue) {
    const Sampler a(type(), 7, 16), b(type(), 7, 16);
    for (uint32_t pixel = 0; pixel < 200; pixel += 7)
        for (uint32_t s = 0; s < 40; ++s)
            for (const DecisionSite& site : kSites) {
                const PixelSample pa = a.at(pixel, s), pb = b.at(pixel, s);
                const float x = pa.get1D(site);
                ASSERT_EQ(x, pa.get1D(site));  // drawing mutates nothing
                ASSERT_EQ(x, pb.get1D(site));  // nor does it depend on the Sampler object
                const Vec2 p = pa.get2D(site), q = pb.get2D(site);
                ASSERT_EQ(p.x, q.x);
                ASSERT_EQ(p.y, q.y);
                // Order of drawing does not matter.
                const Vec2 r = b.at(pixel, s).get2D(site);
                ASSERT_EQ(p.x, r.x);
                ASSERT_EQ(p.y, r.y);
            }
}

// Streams of 16 samples × 2-D values that differ in one coordinate (seed, pixel, decision,
// vertex, repeat) must differ almost everywhere.
TEST_P(EachSampler, DifferentCoordinatesGiveDifferentStreams) {
    const Sampler a(type(), 7, 16), otherSeed(type(), 8, 16);
    struct Variant {
        const char* what;
        std::function<Vec2(uint32_t pixel, uint32_t s)> value;
    };
    auto base = [&](uint32_t px, uint32_t s) {
        return a.at(px, s).get2D(DecisionSite{Decision::LightPoint, 1, 0, 2});
    };
    const std::vector<Variant> variants = {
        {"seed",
         [&](uint32_t px, uint32_t s) {
             return otherSeed.at(px, s).get2D(DecisionSite{Decision::LightPoint, 1, 0, 2});
         }},
        {"pixel",
         [&](uint32_t px, uint32_t s) {
             return a.at(px + 1, s).get2D(DecisionSite{Decision::LightPoint, 1, 0, 2});
         }},
        {"decision",
         [&](uint32_t px, uint32_t s) {
             return a.at(px, s).get2D(DecisionSite{Decision::BsdfDirection, 1, 0, 2});
         }},
        {"vertex",
         [&](uint32_t px, uint32_t s) {
             return a.at(px, s).get2D(DecisionSite{Decision::LightPoint, 2, 0, 2});
         }},
        {"repeat",
         [&](uint32_t px, uint32_t s) {
             return a.at(px, s).get2D(DecisionSite{Decision::LightPoint, 1, 1, 2});
         }},
        {"sample set",
         [&](uint32_t px, uint32_t s) {
             return a.at(px, s + 16).get2D(DecisionSite{Decision::LightPoint, 1, 0, 2});
         }},
    };
    for (const Variant& v : variants) {
        int equal = 0, total = 0;
        for (uint32_t px = 0; px < 100; ++px)
            for (uint32_t s = 0; s < 16; ++s) {
                const Vec2 p = base(px, s), q = v.value(px, s);
                equal += (p.x == q.x) + (p.y == q.y);
                total += 2;
            }
        EXPECT_LT(equal, total / 100) << name() << ": changing the " << v.what << " leaves "
                                      << equal << " of " << total << " values unchanged";
    }
}

// --- Range ------------------------------------------------------------------------------------

TEST_P(EachSampler, EveryCoordinateIsInUnitInterval) {
    for (uint32_t setSize : {1u, 2u, 7u, 16u, 100u, 256u, 4096u, 65536u}) {
        const Sampler s(type(), 3, setSize);
        for (uint32_t pixel : {0u, 1u, 12345u, 0xffffffffu})
            for (uint32_t i = 0; i < 600; ++i) {
                // Samples at the start and at the end of the first sets, and far out.
                const uint32_t sample =
                    i < 200 ? i : (i < 400 ? setSize - 200 + i : 0xffffff00u + i);
                const PixelSample ps = s.at(pixel, sample);
                for (uint32_t repeatCount : {1u, 3u, 16u}) {
                    const DecisionSite site{Decision::LightPoint, 1, i % repeatCount, repeatCount};
                    const float x = ps.get1D(site);
                    const Vec2 p = ps.get2D(site);
                    ASSERT_TRUE(x >= 0.0f && x < 1.0f) << name() << " set " << setSize << ": " << x;
                    ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f) << name() << ": " << p.x;
                    ASSERT_TRUE(p.y >= 0.0f && p.y < 1.0f) << name() << ": " << p.y;
                }
            }
    }
}

// --- Uniformity (χ²) ----------------------------------------------------------------------------

// Draws from all sample indices, one draw per pixel: the χ² test needs independent
// observations, and only pixels are independent — a structured sampler's set is dependent by
// design (a Hammersley set is one rigidly rotated lattice, so pooling a pixel's draws would
// over-disperse the statistic, and jittered strata would under-disperse it). Cycling the
// index with the pixel still covers every position of the set.
TEST_P(EachSampler, DrawsFromEveryIndexAreUniform1D) {
    const Sampler s(type(), 11, 16);
    UnitHistogram h(1000);
    for (uint32_t pixel = 0; pixel < 1000000; ++pixel)
        h.add(s.at(pixel, pixel % 16).get1D(Decision::Time));
    kChi2.expectFits(h.test(1e6), name() + " every index, 1-D");
}

// 2-D over a 12-sample set (a 3 × 4 strata grid for the stratified sampler).
TEST_P(EachSampler, DrawsFromEveryIndexAreUniform2D) {
    const Sampler s(type(), 12, 12);
    PlaneHistogram h(100, 100, 0, 1, 0, 1);
    for (uint32_t pixel = 0; pixel < 1000000; ++pixel)
        h.add(s.at(pixel, pixel % 12).get2D(Decision::LightPoint, 1));
    kChi2.expectFits(planeUniformChi2(h, 1e6), name() + " every index, 2-D");
}

// A single sample index across 10⁶ pixels: the Cranley–Patterson rotation alone must make each
// coordinate uniform (without it Hammersley's x = k/n would take 16 values).
TEST_P(EachSampler, OneSampleIndexIsUniformAcrossPixels1D) {
    const Sampler s(type(), 13, 16);
    UnitHistogram h(1000);
    for (uint32_t pixel = 0; pixel < 1000000; ++pixel)
        h.add(s.at(pixel, 5).get1D(Decision::Time));
    kChi2.expectFits(h.test(1e6), name() + " sample 5, 1-D");
}

TEST_P(EachSampler, OneSampleIndexIsUniformAcrossPixels2D) {
    const Sampler s(type(), 14, 16);
    PlaneHistogram h(100, 100, 0, 1, 0, 1);
    for (uint32_t pixel = 0; pixel < 1000000; ++pixel)
        h.add(s.at(pixel, 21).get2D(Decision::BsdfDirection, 2));
    kChi2.expectFits(planeUniformChi2(h, 1e6), name() + " sample 21, 2-D");
}

// Repeated draws (4 per sample), one per pixel, cycling through samples and repeats.
TEST_P(EachSampler, RepeatedDrawsAreUniform) {
    const Sampler s(type(), 15, 16);
    UnitHistogram h(1000);
    for (uint32_t pixel = 0; pixel < 1000000; ++pixel) {
        const uint32_t i = pixel % 16, r = (pixel / 16) % 4;
        h.add(s.at(pixel, i).get1D(DecisionSite{Decision::LightSelect, 1, r, 4}));
    }
    kChi2.expectFits(h.test(1e6), name() + " repeats");
}

// Negative controls: the 1-D set-up rejects a mild distortion x^1.02 of uniform values
// (λ ≈ 380 against 999 degrees of freedom), the 2-D set-up rejects coordinates that are each
// uniform but dependent.
TEST(SamplerChi2NegativeControl, Rejects1DPowerDistortion) {
    const Sampler s(SamplerType::Independent, 11, 16);
    UnitHistogram h(1000);
    for (uint32_t pixel = 0; pixel < 62500; ++pixel)
        for (uint32_t i = 0; i < 16; ++i)
            h.add(std::pow(s.at(pixel, i).get1D(Decision::Time), 1.02f));
    kChi2.expectRejects(h.test(1e6), "x^1.02");
}

TEST(SamplerChi2NegativeControl, Rejects2DDependentCoordinates) {
    const Sampler s(SamplerType::Independent, 12, 12);
    PlaneHistogram h(100, 100, 0, 1, 0, 1);
    const uint32_t pixels = 83333;
    for (uint32_t pixel = 0; pixel < pixels; ++pixel)
        for (uint32_t i = 0; i < 12; ++i) {
            const Vec2 p = s.at(pixel, i).get2D(Decision::LightPoint, 1);
            h.add(Vec2(p.x, float(frac(p.x + 0.5 * p.y))));  // y' is uniform, but depends on x
        }
    kChi2.expectRejects(planeUniformChi2(h, pixels * 12.0), "(x, frac(x + y/2))");
}

// --- Stratification -------------------------------------------------------------------------

const uint32_t kSetSizes[] = {1, 2, 3, 7, 12, 16, 64, 100, 256};

TEST_P(EachStructuredSampler, OneDimensionalSetsAreStratified) {
    for (uint32_t n : kSetSizes) {
        const Sampler s(type(), 21, n);
        const uint32_t pixels = n >= 100 ? 20 : 200;
        for (uint32_t pixel = 0; pixel < pixels; ++pixel)
            for (uint32_t set = 0; set < 2; ++set)
                for (const DecisionSite& site :
                     {DecisionSite{Decision::Time}, DecisionSite{Decision::RussianRoulette, 3},
                      DecisionSite{Decision::BsdfLobe, 1}}) {
                    std::vector<float> xs;
                    for (uint32_t i = 0; i < n; ++i)
                        xs.push_back(s.at(pixel, set * n + i).get1D(site));
                    const double spread = shiftedStrataSpread(xs);
                    ASSERT_LT(spread, 1.0)
                        << name() << ", set size " << n << ", pixel " << pixel << ", set " << set
                        << ", decision " << site.decision.name;
                    if (type() == SamplerType::Hammersley) {  // a rotated lattice {o + k/n}
                        ASSERT_LT(spread, 1e-3) << "set size " << n << ", pixel " << pixel;
                    }
                }
    }
}

TEST_P(EachStructuredSampler, TwoDimensionalSetsAreStratified) {
    for (uint32_t n : kSetSizes) {
        const Sampler s(type(), 22, n);
        const uint32_t pixels = n >= 100 ? 10 : 100;
        for (uint32_t pixel = 0; pixel < pixels; ++pixel)
            for (uint32_t set = 0; set < 2; ++set)
                for (const DecisionSite& site : {DecisionSite{Decision::LightPoint},
                                                 DecisionSite{Decision::BsdfDirection, 2}}) {
                    std::vector<Vec2> ps;
                    std::vector<float> xs, ys;
                    for (uint32_t i = 0; i < n; ++i) {
                        ps.push_back(s.at(pixel, set * n + i).get2D(site));
                        xs.push_back(ps.back().x);
                        ys.push_back(ps.back().y);
                    }
                    const std::string where = name() + ", set size " + std::to_string(n) +
                                              ", pixel " + std::to_string(pixel);
                    if (type() != SamplerType::Hammersley) {
                        const int cols = int(gridColumns(n));
                        ASSERT_TRUE(oneInEachShiftedCell(ps, cols, int(n) / cols))
                            << where << ": not one point per cell of the " << cols << " x "
                            << n / cols << " grid";
                    } else {
                        // x is always a rotated lattice; the full net property needs 2^m points.
                        ASSERT_LT(shiftedStrataSpread(xs), 1e-3) << where;
                        if ((n & (n - 1)) == 0) {
                            const std::string defect = hammersleyNetDefect(ps);
                            ASSERT_TRUE(defect.empty()) << where << ": " << defect;
                        }
                    }
                }
    }
}

// With repeatCount r, the setSize·r draws of one pixel set are stratified together; under
// pbrt_v1, the r draws of each pixel sample are (pbrt-v1's sample arrays), and not jointly.
TEST_P(EachStructuredSampler, RepeatsAreStratified) {
    struct Case {
        uint32_t setSize, repeats;
    };
    const bool perSample = type() == SamplerType::PbrtV1;
    for (const Case c :
         {Case{1, 4}, Case{4, 2}, Case{4, 4}, Case{16, 4}, Case{6, 3}, Case{5, 7}, Case{4, 9}}) {
        const Sampler s(type(), 23, c.setSize);
        const uint32_t n = c.setSize * c.repeats;
        for (uint32_t pixel = 0; pixel < 100; ++pixel) {
            std::vector<float> xs;
            std::vector<Vec2> ps;
            for (uint32_t i = 0; i < c.setSize; ++i) {
                std::vector<float> sampleXs;
                std::vector<Vec2> samplePs;
                for (uint32_t r = 0; r < c.repeats; ++r) {
                    const PixelSample sample = s.at(pixel, c.setSize + i);  // the second set
                    sampleXs.push_back(
                        sample.get1D(DecisionSite{Decision::LightSelect, 1, r, c.repeats}));
                    samplePs.push_back(
                        sample.get2D(DecisionSite{Decision::LightPoint, 1, r, c.repeats}));
                }
                if (perSample) {
                    const int cols = int(gridColumns(c.repeats));
                    ASSERT_TRUE(oneInEachShiftedStratum(sampleXs)) << "pixel " << pixel;
                    ASSERT_TRUE(oneInEachShiftedCell(samplePs, cols, int(c.repeats) / cols))
                        << "pixel " << pixel << ", sample " << i << ", " << c.repeats << " repeats";
                }
                xs.insert(xs.end(), sampleXs.begin(), sampleXs.end());
                ps.insert(ps.end(), samplePs.begin(), samplePs.end());
            }
            const std::string where = name() + ", " + std::to_string(c.setSize) + " samples x " +
                                      std::to_string(c.repeats) + " repeats, pixel " +
                                      std::to_string(pixel);
            if (perSample) {
                // 16 samples' independent sets of 4 fill the 64 shifted strata one each only
                // if their 16 rotations fall in 16 different sixteenths of a stratum's width:
                // 16!/16¹⁶ ≈ 10⁻⁶ per pixel.
                if (c.setSize == 16) {
                    EXPECT_FALSE(oneInEachShiftedStratum(xs)) << where;
                }
                continue;
            }
            ASSERT_TRUE(oneInEachShiftedStratum(xs)) << where << " (1-D)";
            if (type() == SamplerType::Stratified) {
                const int cols = int(gridColumns(n));
                ASSERT_TRUE(oneInEachShiftedCell(ps, cols, int(n) / cols)) << where << " (2-D)";
            } else if ((n & (n - 1)) == 0) {
                const std::string defect = hammersleyNetDefect(ps);
                ASSERT_TRUE(defect.empty()) << where << " (2-D): " << defect;
            }
        }
    }
}

// The checks above must be able to fail: independent samples are almost never stratified.
TEST(StratificationNegativeControl, IndependentSamplesAreNotStratified) {
    const Sampler s(SamplerType::Independent, 21, 16);
    int stratified1D = 0, stratified2D = 0, nets = 0;
    for (uint32_t pixel = 0; pixel < 100; ++pixel) {
        std::vector<float> xs;
        std::vector<Vec2> ps;
        for (uint32_t i = 0; i < 16; ++i) {
            xs.push_back(s.at(pixel, i).get1D(Decision::Time));
            ps.push_back(s.at(pixel, i).get2D(Decision::LightPoint));
        }
        stratified1D += oneInEachShiftedStratum(xs);
        stratified2D += oneInEachShiftedCell(ps, 4, 4);
        nets += hammersleyNetDefect(ps).empty();
    }
    EXPECT_EQ(stratified1D, 0);
    EXPECT_EQ(stratified2D, 0);
    EXPECT_EQ(nets, 0);
    // Nor is a stratified 2-D set a Hammersley net, and a shifted-stratum check with the wrong
    // grid fails.
    const Sampler st(SamplerType::Stratified, 21, 16);
    std::vector<Vec2> ps;
    for (uint32_t i = 0; i < 16; ++i)
        ps.push_back(st.at(0, i).get2D(Decision::LightPoint));
    EXPECT_FALSE(hammersleyNetDefect(ps).empty());
    EXPECT_TRUE(oneInEachShiftedCell(ps, 4, 4));
    EXPECT_FALSE(oneInEachShiftedCell(ps, 2, 8));
}

// --- Independence of decisions (correlation z-tests) ------------------------------------------

// Mean of (a − ½)(b − ½) over all samples of `pixels` pixels, z-tested against 0 with the
// pixels as independent units (samples within a pixel set are not independent).
struct Correlation {
    double mean, standardError;
    double z() const { return mean / standardError; }
};
Correlation correlation(uint32_t pixels, uint32_t samples,
                        const std::function<std::pair<float, float>(uint32_t, uint32_t)>& pair) {
    double sum = 0, sum2 = 0;
    for (uint32_t px = 0; px < pixels; ++px) {
        double perPixel = 0;
        for (uint32_t s = 0; s < samples; ++s) {
            const auto [a, b] = pair(px, s);
            perPixel += (double(a) - 0.5) * (double(b) - 0.5);
        }
        sum += perPixel;
        sum2 += perPixel * perPixel;
    }
    const double mean = sum / pixels;
    const double variance = (sum2 - pixels * mean * mean) / (pixels - 1);
    return {mean / samples, std::sqrt(variance / pixels) / samples};
}

TEST_P(EachSampler, DifferentDecisionsAreUncorrelated) {
    const Sampler s(type(), 31, 16);
    struct Pair {
        const char* what;
        std::function<std::pair<float, float>(uint32_t, uint32_t)> values;
    };
    const std::vector<Pair> pairs = {
        {"time / light selection",
         [&](uint32_t px, uint32_t i) {
             const PixelSample p = s.at(px, i);
             return std::pair(p.get1D(Decision::Time), p.get1D(Decision::LightSelect));
         }},
        {"bsdf lobe at vertices 0 / 1",
         [&](uint32_t px, uint32_t i) {
             const PixelSample p = s.at(px, i);
             return std::pair(p.get1D(Decision::BsdfLobe, 0), p.get1D(Decision::BsdfLobe, 1));
         }},
        {"light point x / bsdf direction x",
         [&](uint32_t px, uint32_t i) {
             const PixelSample p = s.at(px, i);
             return std::pair(p.get2D(Decision::LightPoint).x, p.get2D(Decision::BsdfDirection).x);
         }},
        {"lens x / lens y",
         [&](uint32_t px, uint32_t i) {
             const Vec2 v = s.at(px, i).get2D(Decision::Lens);
             return std::pair(v.x, v.y);
         }},
        {"neighbouring pixels",
         [&](uint32_t px, uint32_t i) {
             return std::pair(s.at(2 * px, i).get1D(Decision::RussianRoulette, 2),
                              s.at(2 * px + 1, i).get1D(Decision::RussianRoulette, 2));
         }},
    };
    for (const Pair& pair : pairs) {
        const Correlation c = correlation(62500, 16, pair.values);
        std::printf("[z] %s, %s: E[(a-1/2)(b-1/2)] = %.3g +- %.2g, z = %.2f\n", name().c_str(),
                    pair.what, c.mean, c.standardError, c.z());
        EXPECT_LT(std::abs(c.z()), kZ)
            << name() << ", " << pair.what << ": mean " << c.mean << " ± " << c.standardError;
    }
}

// A correlation of 0.02 (b = 0.98·b + 0.02·a) must be detected.
TEST(CorrelationNegativeControl, DetectsAWeakCorrelation) {
    const Sampler s(SamplerType::Stratified, 31, 16);
    const Correlation c = correlation(62500, 16, [&](uint32_t px, uint32_t i) {
        const PixelSample p = s.at(px, i);
        const float a = p.get1D(Decision::Time);
        return std::pair(a, 0.98f * p.get1D(Decision::LightSelect) + 0.02f * a);
    });
    std::printf("[z, negative control] weak correlation: z = %.2f\n", c.z());
    EXPECT_GT(std::abs(c.z()), kZ);
}

INSTANTIATE_TEST_SUITE_P(Samplers, EachSampler, ::testing::ValuesIn(kAllTypes), typeName);
INSTANTIATE_TEST_SUITE_P(Samplers, EachStructuredSampler, ::testing::ValuesIn(kStructuredTypes),
                         typeName);

}  // namespace
}  // namespace rr::test
