// Per-pixel records an estimator keeps at pixel samples' first hits besides radiance
// (DirectLightingEstimator::pixelRecords: PMC-HI's final mixture weights, Lai et al. 2007
// fig. 7), summed per pixel with a count and written as the mean over the pixel's samples that
// recorded something. Between the iterations of a schedule that renders in iterations (PMC-IP)
// the means so far are committed, and the next iteration's estimates at the pixel start from
// them (§6.1's feedback). Each pixel is only written by the one unit of work rendering it, in
// sample order, and commits happen between rounds, so everything is bit-identical for any
// thread count.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "config/config_error.h"
#include "integrators/integrator.h"

namespace rr {

struct PixelRecordLayout {
    std::vector<std::string> names;  // the channels
    std::string description;         // what each holds (the output's channel list)
    // The estimator's key that reads the committed records (PMC-HI's `feedback`), which only
    // a schedule in iterations commits: refused under any other; empty: none.
    std::string readsCommitted;
};

// One pixel's place in the records, as a first-hit vertex sees it.
struct PixelRecordSlot {
    double* sums = nullptr;        // where its record goes, then the count; nullptr: none kept
    const float* start = nullptr;  // the means committed last; nullptr: none yet
    uint32_t fields = 0;

    // Adds one sample's values to the pixel's record.
    void add(std::span<const float> values) const {
        if (!sums) return;
        if (values.size() != fields) throw std::logic_error("a pixel record of the wrong size");
        for (size_t i = 0; i < fields; ++i)
            sums[i] += values[i];
        sums[fields] += 1;
    }
};

class PixelRecords {
  public:
    // Sized for a width × height image of the layout's fields (none: nothing is kept);
    // `iterated`: the schedule commits the records between iterations; `estimator`: the JSON
    // pointer of the estimator that made the layout, for the error when it needs commits the
    // schedule will not make.
    void begin(int width, int height, bool iterated, PixelRecordLayout layout,
               const std::string& estimator) {
        if (!iterated && !layout.readsCommitted.empty())
            throw ConfigError(estimator + "/" + layout.readsCommitted,
                              "starts from the records of earlier iterations, which only a "
                              "schedule in iterations makes (pmc_ip)");
        layout_ = std::move(layout);
        width_ = width;
        sums_.assign(layout_.names.empty() ? 0 : size_t(width) * height * stride(), 0.0);
        starts_.clear();
    }
    PixelRecordSlot slot(int x, int y) {
        if (sums_.empty()) return {};
        const size_t pixel = size_t(y) * width_ + x;
        const float* start = nullptr;
        if (!starts_.empty() && starts_[pixel * stride() + fields()] > 0)
            start = &starts_[pixel * stride()];
        return {&sums_[pixel * stride()], start, uint32_t(fields())};
    }
    // The means so far become the pixels' starts (pixels without a record have none).
    void commit() {
        starts_.assign(sums_.size(), 0.0f);
        for (size_t i = 0; i < sums_.size(); i += stride()) {
            const double count = sums_[i + fields()];
            if (count == 0) continue;
            for (size_t f = 0; f < fields(); ++f)
                starts_[i + f] = static_cast<float>(sums_[i + f] / count);
            starts_[i + fields()] = 1;
        }
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
    size_t fields() const { return layout_.names.size(); }
    size_t stride() const { return fields() + 1; }  // the fields and the count (or a flag)

    PixelRecordLayout layout_;
    int width_ = 0;
    std::vector<double> sums_;
    std::vector<float> starts_;  // per pixel: the committed means and 1, or zeros
};

}  // namespace rr
