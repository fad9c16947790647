// Per-pixel records an estimator keeps at pixel samples' first hits besides radiance
// (DirectLightingEstimator::pixelRecordNames: PMC-HI's final mixture weights, Lai et al. 2007
// fig. 7), summed per pixel with a count and written as the mean over the pixel's samples that
// recorded something. Each pixel is only written by the one unit of work rendering it, in
// sample order, so the sums are bit-identical for any thread count.
#pragma once

#include <algorithm>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.h"

namespace rr {

struct PixelRecordLayout {
    std::vector<std::string> names;  // the channels
    std::string description;         // what each holds (the output's channel list)
};

class PixelRecords {
  public:
    // Sized for a width × height image of the layout's fields (none: nothing is kept).
    void begin(int width, int height, PixelRecordLayout layout) {
        layout_ = std::move(layout);
        width_ = width;
        sums_.assign(layout_.names.empty() ? 0 : size_t(width) * height * stride(), 0.0);
    }
    // Where pixel (x, y)'s record goes, or nullptr when none is kept.
    double* at(int x, int y) {
        return sums_.empty() ? nullptr : &sums_[(size_t(y) * width_ + x) * stride()];
    }
    // Adds one sample's values to a pixel's record (`record` from at()).
    static void add(double* record, std::span<const float> values) {
        for (size_t i = 0; i < values.size(); ++i)
            record[i] += values[i];
        record[values.size()] += 1;
    }
    // The means as output channels (0 where no sample recorded).
    std::vector<AuxiliaryChannel> channels() const {
        std::vector<AuxiliaryChannel> out;
        const size_t pixels = sums_.size() / std::max<size_t>(1, stride());
        for (size_t f = 0; f < layout_.names.size(); ++f) {
            AuxiliaryChannel c{layout_.names[f], layout_.description,
                               std::vector<float>(pixels, 0.0f)};
            for (size_t p = 0; p < pixels; ++p) {
                const double* record = &sums_[p * stride()];
                if (record[layout_.names.size()] > 0)
                    c.values[p] = static_cast<float>(record[f] / record[layout_.names.size()]);
            }
            out.push_back(std::move(c));
        }
        return out;
    }

  private:
    size_t stride() const { return layout_.names.size() + 1; }  // the fields and the count

    PixelRecordLayout layout_;
    int width_ = 0;
    std::vector<double> sums_;
};

}  // namespace rr
