#include "techniques/pmc/sample_record.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace rr::pmc {

SampleRecord::SampleRecord(int width, int height, const ReconstructionFilter& filter)
    : width_(width),
      height_(height),
      filter_(filter),
      taps_(2 * filter.reach() + 1),
      counts_(size_t(width) * height, 0),
      varianceCounts_(counts_.size(), 0),
      positive_(counts_.size() * size_t(taps_) * size_t(taps_)) {}

void SampleRecord::beginIteration(const std::vector<uint32_t>& counts, std::vector<double> density,
                                  bool pilot) {
    if (counts.size() != counts_.size() || density.size() != counts_.size())
        throw std::logic_error("an iteration needs one count and one density per pixel");
    pilot_ = pilot;
    if (pilot) return;
    Iteration it;
    it.first.resize(counts.size() + 1);
    uint64_t total = 0;
    for (size_t p = 0; p < counts.size(); ++p) {
        it.first[p] = static_cast<uint32_t>(total);
        total += counts[p];
    }
    if (total > UINT32_MAX) throw std::runtime_error("pmc_ip: too many samples in an iteration");
    it.first[counts.size()] = static_cast<uint32_t>(total);
    it.samples.resize(total);
    it.density = std::move(density);
    iterations_.push_back(std::move(it));
}

void SampleRecord::record(size_t pixel, const std::vector<Rgb>& values,
                          const std::vector<Vec2>& offsets) {
    if (offsets.size() != values.size())
        throw std::logic_error("pmc_ip needs every sample's position in its pixel");
    if (!pilot_) {
        Iteration& it = iterations_.back();
        const uint32_t first = it.first[pixel];
        if (values.size() != it.first[pixel + 1] - first)
            throw std::logic_error("pmc_ip got another number of samples than it planned");
        for (size_t i = 0; i < values.size(); ++i)
            it.samples[first + i] = {offsets[i], values[i]};
        counts_[pixel] += static_cast<uint32_t>(values.size());
    }
    // The variance sums: this pixel's samples towards each target within reach.
    PositiveSums* sums = &positive_[pixel * size_t(taps_) * size_t(taps_)];
    ReconstructionFilter::Taps wx, wy;
    for (size_t i = 0; i < values.size(); ++i) {
        filter_.taps(offsets[i].x, &wx);
        filter_.taps(offsets[i].y, &wy);
        const double y = values[i].luminance();
        for (int ty = wy.first; ty <= wy.last; ++ty) {
            if (!(wy.weight[size_t(ty)] > 0)) continue;
            for (int tx = wx.first; tx <= wx.last; ++tx) {
                const double w = std::max(0.0, wx.weight[size_t(tx)]) * wy.weight[size_t(ty)];
                if (w == 0) continue;
                PositiveSums& s = sums[ty * taps_ + tx];
                s.weight += w;
                s.squaredWeight += w * w;
                s.weightedY += w * y;
                s.weightedYSquares += w * y * y;
            }
        }
    }
    varianceCounts_[pixel] += static_cast<uint32_t>(values.size());
}

void SampleRecord::clearVarianceSums() {
    std::fill(positive_.begin(), positive_.end(), PositiveSums{});
    std::fill(varianceCounts_.begin(), varianceCounts_.end(), 0u);
}

void SampleRecord::varianceImage(std::vector<double>* variance,
                                 std::vector<double>* luminance) const {
    variance->assign(counts_.size(), 0.0);
    luminance->assign(counts_.size(), 0.0);
    const int reach = filter_.reach();
    tbb::parallel_for(
        tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < width_; ++x) {
                    // Sources p = target + (dx, dy); the target is tap (reach − dx, reach − dy) of
                    // p.
                    double v = 0, v2 = 0, vy = 0, vy2 = 0;
                    for (int dy = -reach; dy <= reach; ++dy) {
                        const int py = y + dy;
                        if (py < 0 || py >= height_) continue;
                        for (int dx = -reach; dx <= reach; ++dx) {
                            const int px = x + dx;
                            if (px < 0 || px >= width_) continue;
                            const size_t p = size_t(py) * width_ + px;
                            if (varianceCounts_[p] == 0) continue;
                            const double scale = 1.0 / varianceCounts_[p];
                            const PositiveSums& s =
                                positive_[p * size_t(taps_) * size_t(taps_) +
                                          size_t((reach - dy) * taps_ + (reach - dx))];
                            v += scale * s.weight;
                            v2 += scale * scale * s.squaredWeight;
                            vy += scale * s.weightedY;
                            vy2 += scale * s.weightedYSquares;
                        }
                    }
                    const size_t k = size_t(y) * width_ + x;
                    if (!(v > 0)) continue;
                    const double mean = vy / v;
                    const double effective = v * v / v2;
                    (*luminance)[k] = mean;
                    if (effective > 1)
                        (*variance)[k] =
                            std::max(0.0, vy2 / v - mean * mean) * effective / (effective - 1);
                }
        });
}

template <class Scale>
void SampleRecord::gather(const std::vector<size_t>& iterations, const Scale& scale,
                          std::vector<SplatSums>* out) const {
    out->assign(counts_.size(), SplatSums{});
    const int reach = filter_.reach();
    tbb::parallel_for(
        tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y) {
                SplatSums* row = &(*out)[size_t(y) * width_];
                // Sources in row-major order, each one's samples iteration by iteration.
                for (int py = std::max(0, y - reach); py <= std::min(height_ - 1, y + reach); ++py)
                    for (int px = 0; px < width_; ++px) {
                        const size_t p = size_t(py) * width_ + px;
                        const int x0 = std::max(0, px - reach),
                                  x1 = std::min(width_ - 1, px + reach);
                        for (size_t t : iterations) {
                            const Iteration& it = iterations_[t];
                            for (uint32_t i = it.first[p]; i < it.first[p + 1]; ++i) {
                                const double s = scale(t, p, i - it.first[p]);
                                if (s == 0) continue;
                                const StoredSample& sample = it.samples[i];
                                const SplatTerms terms(sample.value);
                                const double wy =
                                    filter_.weight1D(double(py - y) + sample.offset.y - 0.5) * s;
                                if (wy == 0) continue;
                                for (int x = x0; x <= x1; ++x) {
                                    const double w =
                                        filter_.weight1D(double(px - x) + sample.offset.x - 0.5) *
                                        wy;
                                    if (w != 0) row[x].add(w, terms);
                                }
                            }
                        }
                    }
            }
        });
}

double SampleRecord::filterArea(int x, int y) const {
    // Offsets u − c of the film's edges from the pixel's centre.
    return filter_.integral1D(-x - 0.5, width_ - x - 0.5) *
           filter_.integral1D(-y - 0.5, height_ - y - 0.5);
}

std::vector<Rgb> SampleRecord::controlled(const std::vector<SplatSums>& sums,
                                          const std::vector<Rgb>& control) const {
    std::vector<Rgb> estimate(counts_.size());
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const size_t k = size_t(y) * width_ + x;
            const double area = filterArea(x, y);
            float e[3];
            for (int c = 0; c < 3; ++c) {
                const double cv = control[k][c];
                e[c] =
                    static_cast<float>(cv + (sums[k].weighted(c) - cv * sums[k].weight()) / area);
            }
            estimate[k] = Rgb(e[0], e[1], e[2]);
        }
    return estimate;
}

std::vector<Rgb> SampleRecord::crossControlledEstimate() const {
    // Every pixel has the same count n ≥ 2 in the first iteration; halves of h₁ = ⌈n/2⌉ and
    // h₂ = n − h₁ samples, each with density h per unit area.
    const uint32_t n = iterations_[0].first[1] - iterations_[0].first[0];
    const uint32_t h1 = (n + 1) / 2, h2 = n - h1;
    if (h2 == 0) throw std::logic_error("pmc_ip's first iteration needs two samples per pixel");
    std::vector<SplatSums> first, second;
    gather(
        {0}, [&](size_t, size_t, uint32_t i) { return i < h1 ? 1.0 / h1 : 0.0; }, &first);
    gather(
        {0}, [&](size_t, size_t, uint32_t i) { return i < h1 ? 0.0 : 1.0 / h2; }, &second);
    std::vector<Rgb> firstRatio(first.size()), secondRatio(second.size());
    for (size_t k = 0; k < first.size(); ++k) {
        firstRatio[k] = first[k].estimate();
        secondRatio[k] = second[k].estimate();
    }
    const std::vector<Rgb> a = controlled(first, secondRatio), b = controlled(second, firstRatio);
    std::vector<Rgb> estimate(a.size());
    const float wa = float(h1) / float(n), wb = float(h2) / float(n);
    for (size_t k = 0; k < a.size(); ++k)
        estimate[k] = a[k] * wa + b[k] * wb;
    return estimate;
}

std::vector<Rgb> SampleRecord::iterationEstimate(size_t t, const std::vector<Rgb>& control) const {
    if (t == 0) return crossControlledEstimate();
    std::vector<SplatSums> sums;
    gather(
        {t}, [&](size_t, size_t p, uint32_t) { return 1.0 / iterations_[t].density[p]; }, &sums);
    return controlled(sums, control);
}

PixelEstimates SampleRecord::pooledImage(size_t iterations) const {
    std::vector<size_t> all(std::min(iterations, iterations_.size()));
    for (size_t t = 0; t < all.size(); ++t)
        all[t] = t;
    std::vector<SplatSums> sums;
    gather(
        all, [&](size_t, size_t p, uint32_t) { return 1.0 / counts_[p]; }, &sums);
    PixelEstimates out;
    out.values.resize(sums.size());
    out.variances.resize(sums.size());
    for (size_t k = 0; k < sums.size(); ++k) {
        out.values[k] = sums[k].estimate();
        out.variances[k] = sums[k].varianceOfEstimate();
    }
    return out;
}

}  // namespace rr::pmc
