// Sample generators. A coordinate is a pure function of
//   (seed, pixel, sample index, decision site)
// so images do not depend on thread count or scheduling. Structured samplers stratify the
// `setSize` samples of a pixel together (the pixel's spp when known in advance); sample
// index s belongs to set s / setSize, and every set is an independent structured pattern.
// The repeats of a decision (several light samples per pixel sample) are stratified with the
// set's samples, except under pbrt_v1, where each pixel sample's repeats are a jittered set of
// their own, as pbrt-v1 draws its light and BSDF sample arrays. All structured samplers add a
// per-(pixel, decision) Cranley–Patterson rotation, which makes every single coordinate exactly
// uniform, so any prefix of samples is an unbiased estimate.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "math/vector.h"
#include "sampling/decisions.h"
#include "sampling/hash.h"

namespace rr {

enum class SamplerType : uint8_t {
    Independent,  // hashed PCG per coordinate
    Stratified,   // jittered strata, randomly permuted per decision
    Hammersley,   // Hammersley points + per-pixel Cranley–Patterson rotation (two-stage paper)
    // pbrt-v1's sampling (its default best-candidate sampler, samplers/bestcandidate.cpp): the
    // pixel's samples stratified together in each single decision (film position, lens, time,
    // and a path's decisions), as `stratified` does, in place of pbrt-v1's image-wide
    // best-candidate table; a decision drawn n > 1 times per pixel sample gets n jittered strata
    // of its own per pixel sample (StratifiedSample1D/2D; 2-D sets on a grid of the largest
    // divisor of n not above √n: pbrt-v1's integrators ask for squares, RoundSize).
    PbrtV1,
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
    PixelSample(const Sampler* s, uint32_t pixel, uint32_t sample, uint64_t key, uint32_t slot)
        : sampler_(s), key_(key), pixel_(pixel), sample_(sample), slot_(slot) {}
    // Where this sample sits in its structured set for one decision site: the set's pattern
    // key (per pixel, set, decision and vertex), this draw's index among the set's
    // setSize × repeatCount draws, and the (permuted) point of the pattern it takes.
    struct SetPosition {
        uint64_t key;
        uint32_t index, point;
    };
    SetPosition setPosition(const DecisionSite& site, uint32_t repeatCount, uint32_t size) const;
    // The structured set a draw of `site` belongs to: its shape and the draw's place in it.
    struct SetDraw {
        uint32_t size, columns, rows;
        float invSize, invColumns, invRows;
        uint64_t columnsMagic;
        SetPosition position;
    };
    SetDraw setDraw(const DecisionSite& site) const;

    const Sampler* sampler_;
    // Hash of (seed, pixel, sample) for the independent sampler, of (seed, pixel, set) for the
    // structured ones: a draw only mixes it with its decision site.
    uint64_t key_;
    uint32_t pixel_;
    uint32_t sample_;
    uint32_t slot_;  // structured samplers: index of the sample within its set
};

class Sampler {
  public:
    Sampler(SamplerType type, uint32_t seed, uint32_t setSize);

    // The per-pixel and per-sample (or per-set) hashing happens here, once per pixel sample.
    PixelSample at(uint32_t pixel, uint32_t sampleIndex) const {
        const uint64_t pixelKey = mixKey(seedKey_, pixel);
        if (type_ == SamplerType::Independent)
            return PixelSample(this, pixel, sampleIndex, mixKey(pixelKey, sampleIndex), 0);
        const uint32_t set = sampleIndex / setSize_;
        return PixelSample(this, pixel, sampleIndex, mixKey(pixelKey, set),
                           sampleIndex - set * setSize_);
    }
    SamplerType type() const { return type_; }
    uint32_t seed() const { return seed_; }
    uint32_t setSize() const { return setSize_; }

  private:
    friend class PixelSample;
    // The structured pattern of n = setSize_ × repeatCount points, with the reciprocals and
    // the divisor a draw needs, so that draws do not divide.
    struct SetShape {
        uint32_t size;           // n
        uint32_t columns, rows;  // 2-D strata grid: columns × rows = n
        float invSize, invColumns, invRows;
        uint64_t columnsMagic;  // ⌊(2^64 − 1) / columns⌋ + 1 (0 when columns = 1)
    };
    static SetShape makeShape(uint32_t n);
    SetShape shape(uint32_t repeatCount) const {
        return repeatCount <= kCachedRepeatCounts ? shapes_[repeatCount - 1]
                                                  : makeShape(setSize_ * repeatCount);
    }
    // pbrt_v1's set of one pixel sample's repeats.
    SetShape repeatShape(uint32_t repeatCount) const {
        return repeatCount <= kCachedRepeatCounts ? repeatShapes_[repeatCount - 1]
                                                  : makeShape(repeatCount);
    }

    // Repeat counts up to this have their set shape precomputed.
    static constexpr uint32_t kCachedRepeatCounts = 64;

    SamplerType type_;
    uint32_t seed_;
    uint32_t setSize_;
    uint64_t seedKey_;
    std::array<SetShape, kCachedRepeatCounts> shapes_;        // [r − 1]: setSize_ × r points
    std::array<SetShape, kCachedRepeatCounts> repeatShapes_;  // [r − 1]: r points
};

}  // namespace rr
