// PMC-IP's record of its samples (Lai et al. 2007 §4), kept so that its images can weigh each
// sample by the density it was drawn with, through the film's reconstruction filter: eq. (2)'s
// W_ij, "non-zero if u is within the support of the reconstruction filter at (i, j)". Samples
// are stored per iteration, each pixel's in sample order (value and position in the pixel, 20
// bytes), with the density they were drawn with: an iteration that gives pixel p an expected
// n samples draws them with density n per unit area over the pixel.
//
// Three things are read from the record, each a pure function of it (every target pixel sums
// its sources in a fixed order, rows in parallel), so bit-identical for any thread count:
//  - the variance image (§4.2, "the sample variance in power seen among samples that
//    contribute to each pixel"): at each target pixel, the weighted per-sample variance of
//    luminance over the samples within the filter's support, each weighted by the filter's
//    positive part and by 1 / its pixel's sample count, with Kish's effective count n_e =
//    (Σ v)² / Σ v² correcting for few samples: s² = Σ v (Y − m)² / Σ v × n_e / (n_e − 1). For
//    the box filter this is the pixel's own sample variance. Its sums are kept per source pixel
//    and target as samples arrive (32 bytes per pair: 800 per pixel for a radius-2 filter), so
//    each adaptation costs one pass over the pixels, however many samples came before;
//  - an iteration's unbiased estimate (eq. 3 with the iteration's density q):
//    c + Σ w (L − c) / q / W for a control value c fixed before the iteration, W the filter's
//    integral over the film (1 inside it). The first iteration has no earlier image for c, and
//    without one Σ w / q / W, which is 1 only on average, would put the filter weights' own
//    noise into every pixel: its samples are split in two halves (each pixel's first ⌈n/2⌉
//    samples and the rest), each half's ratio image is the other's c, and the two estimates
//    are averaged by their sizes. For the box filter this is the pixel's mean;
//  - the pooled image: Σ w L / n ÷ Σ w / n over every sample, n its pixel's count (a
//    stratified estimate of each pixel's footprint), with the film's variance estimator.
#pragma once

#include <cstdint>
#include <vector>

#include "integrators/integrator.h"
#include "math/rgb.h"
#include "math/vector.h"
#include "render/film.h"
#include "render/reconstruction_filter.h"

namespace rr::pmc {

class SampleRecord {
  public:
    SampleRecord(int width, int height, const ReconstructionFilter& filter);

    int width() const { return width_; }
    int height() const { return height_; }
    size_t pixels() const { return counts_.size(); }

    // A new iteration of `counts` samples per pixel, drawn with `density` per unit area over
    // each pixel (the expected count). A pilot's samples feed the variance image only; they
    // are neither stored nor counted.
    void beginIteration(const std::vector<uint32_t>& counts, std::vector<double> density,
                        bool pilot);
    // Pixel `pixel`'s samples of the current iteration, all at once (by the unit that renders
    // it).
    void record(size_t pixel, const std::vector<Rgb>& values, const std::vector<Vec2>& offsets);
    // Kept samples per pixel so far.
    uint32_t count(size_t pixel) const { return counts_[pixel]; }
    size_t iterations() const { return iterations_.size(); }

    // The variance image over the samples the variance sums hold, n(p) each pixel's count of
    // them: per pixel the per-sample luminance variance and the weighted mean luminance.
    void varianceImage(std::vector<double>* variance, std::vector<double>* luminance) const;
    // Empties the variance sums (after a pilot).
    void clearVarianceSums();

    // Iteration t's estimate c + (Σ w L / q − c Σ w / q) / W per pixel, c = control[pixel]
    // (ignored for the first iteration, which is split in two halves instead).
    std::vector<Rgb> iterationEstimate(size_t t, const std::vector<Rgb>& control) const;
    // The pooled image and its variance, over the first `iterations` iterations (all of them by
    // default).
    PixelEstimates pooledImage(size_t iterations = SIZE_MAX) const;

  private:
    struct StoredSample {
        Vec2 offset;
        Rgb value;
    };
    struct Iteration {
        std::vector<uint32_t> first;  // per pixel, and one past the last
        std::vector<double> density;
        std::vector<StoredSample> samples;
    };
    // Per source pixel and each target within reach: Σ v, Σ v², Σ v Y, Σ v Y² with v the
    // filter's positive part.
    struct PositiveSums {
        double weight = 0, squaredWeight = 0, weightedY = 0, weightedYSquares = 0;
    };

    // Sums into out[pixel] every sample of `iterations` splatted with weight w × scale(t, p, i),
    // i the sample's index among its pixel's samples of iteration t (scale 0: left out).
    template <class Scale>
    void gather(const std::vector<size_t>& iterations, const Scale& scale,
                std::vector<SplatSums>* out) const;
    // The filter's integral over the film for the pixel at (x, y).
    double filterArea(int x, int y) const;
    // c + (Σ w L − c Σ w) / W per pixel from the sums of one gather.
    std::vector<Rgb> controlled(const std::vector<SplatSums>& sums,
                                const std::vector<Rgb>& control) const;
    // The first iteration's estimate, its halves controlling each other.
    std::vector<Rgb> crossControlledEstimate() const;

    int width_, height_;
    ReconstructionFilter filter_;
    int taps_;  // 2 reach + 1
    std::vector<uint32_t> counts_;
    std::vector<Iteration> iterations_;
    bool pilot_ = false;                    // the current iteration is a pilot
    std::vector<uint32_t> varianceCounts_;  // samples in the variance sums, per pixel
    std::vector<PositiveSums> positive_;    // [pixel × taps² + tap]
};

}  // namespace rr::pmc
