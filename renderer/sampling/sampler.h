// Sample generators. A coordinate is a pure function of
//   (seed, pixel, sample index, decision site)
// so images do not depend on thread count or scheduling. Structured samplers stratify the
// `setSize` samples of a pixel together (the pixel's spp when known in advance); sample
// index s belongs to set s / setSize, and every set is an independent structured pattern.
// All three add a per-(pixel, decision) Cranley–Patterson rotation, which makes every single
// coordinate exactly uniform, so any prefix of samples is an unbiased estimate.
#pragma once

#include <cstdint>
#include <string_view>

#include "math/vector.h"
#include "sampling/decisions.h"

namespace rr {

enum class SamplerType : uint8_t {
    Independent,  // hashed PCG per coordinate
    Stratified,   // jittered strata, randomly permuted per decision
    Hammersley,   // Hammersley points + per-pixel Cranley–Patterson rotation (two-stage paper)
};

const char* samplerName(SamplerType type);
bool parseSamplerType(std::string_view name, SamplerType* out);

class Sampler;

// The coordinates of one pixel sample. Cheap to copy; no state is mutated by drawing.
class PixelSample {
  public:
    float get1D(const DecisionSite& site) const;
    Vec2 get2D(const DecisionSite& site) const;

    float get1D(Decision d, uint32_t vertex = 0) const { return get1D(DecisionSite{d, vertex}); }
    Vec2 get2D(Decision d, uint32_t vertex = 0) const { return get2D(DecisionSite{d, vertex}); }

    uint32_t pixel() const { return pixel_; }
    uint32_t sampleIndex() const { return sample_; }

  private:
    friend class Sampler;
    PixelSample(const Sampler* s, uint32_t pixel, uint32_t sample)
        : sampler_(s), pixel_(pixel), sample_(sample) {}
    // Where this sample sits in its structured set for one decision site: the set's pattern
    // key, the set size, this draw's index, and the (permuted) point of the pattern it takes.
    struct SetPosition {
        uint64_t key;
        uint32_t size, index, point;
    };
    SetPosition setPosition(const DecisionSite& site) const;

    const Sampler* sampler_;
    uint32_t pixel_;
    uint32_t sample_;
};

class Sampler {
  public:
    Sampler(SamplerType type, uint32_t seed, uint32_t setSize);

    PixelSample at(uint32_t pixel, uint32_t sampleIndex) const {
        return PixelSample(this, pixel, sampleIndex);
    }
    SamplerType type() const { return type_; }
    uint32_t seed() const { return seed_; }
    uint32_t setSize() const { return setSize_; }

  private:
    friend class PixelSample;
    SamplerType type_;
    uint32_t seed_;
    uint32_t setSize_;
    uint32_t gridColumns_;  // 2-D strata: gridColumns_ × (setSize_ / gridColumns_)
};

}  // namespace rr
