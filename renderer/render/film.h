// The image being rendered, accumulated in double precision, and each pixel's count of its own
// samples (the `samples` channel).
//  - Box filter (the default): a pixel is the mean of its own samples; it keeps their sum and
//    sum of squares, from which the mean and the variance of the mean follow. Each pixel is
//    written only by the one unit that renders it, in sample order.
//  - Any other filter (reconstruction_filter.h): every sample is splatted to each pixel centre
//    within the filter's radius, and a pixel is the ratio estimate R = Σ w·L / Σ w (pbrt-v1's
//    film). Its variance is the linearised (delta-method) variance of that ratio with Kish's
//    small-count correction, Σ w²(L − R)² / ((Σ w)² − Σ w²): for equal weights, the sample
//    variance over n − 1, divided by n, as for the box. Neighbouring pixels share samples, so
//    their errors are correlated.
// A splatting film is bit-identical for any thread count: each unit of a round splats into a
// tile of its own, and endRound() adds the tiles to the image in unit order (units are fixed by
// the schedule, never by the threads). The sums then depend on how samples are cut into rounds,
// so schedules cut them by a plan fixed by the settings (ScheduleInputs::splattingFilm).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "math/rgb.h"
#include "math/vector.h"
#include "render/reconstruction_filter.h"

namespace rr {

// Two doubles in one SIMD register (GCC's vector extension; SSE2 on x86-64): elementwise IEEE
// arithmetic, so the sums are those of scalar code.
typedef double Double2 __attribute__((vector_size(16)));

// A sample's value as the sums take it, in pairs: (L_r, L_g), (L_b, 1) for Σ w·L and Σ w;
// (L_r², L_g²), (L_b², 1) for Σ w²·L² and Σ w²; (L_r, L_g), (L_b, 0) for Σ w²·L.
struct SplatTerms {
    Double2 terms[6];
    explicit SplatTerms(const Rgb& v)
        : terms{{v.r, v.g},
                {v.b, 1.0},
                {double(v.r) * v.r, double(v.g) * v.g},
                {double(v.b) * v.b, 1.0},
                {v.r, v.g},
                {v.b, 0.0}} {}
};

// What a splatted pixel keeps, as SplatTerms lays it out: Σ w·L and Σ w for the estimate,
// Σ w²·L², Σ w² and Σ w²·L for its variance.
struct SplatSums {
    Double2 sums[6] = {};

    // A sample with weight w.
    void add(double w, const SplatTerms& t) {
        const Double2 w1 = {w, w}, w2 = w1 * w1;
        sums[0] += w1 * t.terms[0];
        sums[1] += w1 * t.terms[1];
        sums[2] += w2 * t.terms[2];
        sums[3] += w2 * t.terms[3];
        sums[4] += w2 * t.terms[4];
        sums[5] += w2 * t.terms[5];
    }
    void add(double w, const Rgb& v) { add(w, SplatTerms(v)); }
    void add(const SplatSums& o) {
        for (int i = 0; i < 6; ++i)
            sums[i] += o.sums[i];
    }
    double weighted(int c) const { return c < 2 ? sums[0][c] : sums[1][0]; }
    double weight() const { return sums[1][1]; }
    double squaredWeightedSquares(int c) const { return c < 2 ? sums[2][c] : sums[3][0]; }
    double squaredWeight() const { return sums[3][1]; }
    double squaredWeighted(int c) const { return c < 2 ? sums[4][c] : sums[5][0]; }
    Rgb estimate() const;
    Rgb varianceOfEstimate() const;
};

// One unit's splats in one round: a rectangle of pixels covering the unit's pixels and the
// filter's reach around them.
class SplatTile {
  public:
    // Covers pixels [x0, x1) × [y0, y1), all sums zero.
    void reset(int x0, int y0, int x1, int y1);
    bool empty() const { return x1_ <= x0_ || y1_ <= y0_; }
    // The sample at film position (x + offset.x, y + offset.y), weighted by `scale` (1 / the
    // sampling density; 1 for uniform sampling) and the filter.
    void add(const ReconstructionFilter& filter, int x, int y, Vec2 offset, const Rgb& value,
             double scale = 1);
    int x0() const { return x0_; }
    int y0() const { return y0_; }
    int x1() const { return x1_; }
    int y1() const { return y1_; }
    const SplatSums& at(int x, int y) const {
        return sums_[size_t(y - y0_) * size_t(x1_ - x0_) + size_t(x - x0_)];
    }

  private:
    int x0_ = 0, y0_ = 0, x1_ = 0, y1_ = 0;
    std::vector<SplatSums> sums_;
};

class Film {
  public:
    Film(int width, int height, const ReconstructionFilter& filter = ReconstructionFilter());

    int width() const { return width_; }
    int height() const { return height_; }
    const ReconstructionFilter& filter() const { return filter_; }
    bool splats() const { return !filter_.isBox(); }

    // Box film: the next sample of pixel (x, y).
    void add(int x, int y, const Rgb& value);

    // Splatting film. Before a round of `units` units:
    void beginRound(size_t units);
    // The tile of unit `unit`, covering pixels [x0, x1) × [y0, y1) and the filter's reach
    // around them (empty bounds: the unit keeps nothing).
    SplatTile& openTile(size_t unit, int x0, int y0, int x1, int y1);
    // A sample of pixel (x, y) was splatted: its own count.
    void countSample(int x, int y) { ++counts_[size_t(y) * width_ + x]; }
    // Adds the round's tiles to the image in unit order (in parallel over rows, under the
    // caller's task arena).
    void endRound();

    Rgb mean(int x, int y) const;
    // The variance of the pixel estimate (0 with fewer than 2 samples, or for a splatted pixel
    // whose weights leave no effective second sample).
    Rgb varianceOfMean(int x, int y) const;
    uint32_t sampleCount(int x, int y) const { return counts_[size_t(y) * width_ + x]; }

  private:
    struct Pixel {
        double sum[3] = {0, 0, 0};
        double sumSquares[3] = {0, 0, 0};
    };
    size_t index(int x, int y) const { return size_t(y) * width_ + x; }

    int width_, height_;
    ReconstructionFilter filter_;
    std::vector<uint32_t> counts_;
    std::vector<Pixel> pixels_;    // box
    std::vector<SplatSums> sums_;  // splatting
    std::vector<SplatTile> tiles_;
    size_t roundUnits_ = 0;
};

}  // namespace rr
