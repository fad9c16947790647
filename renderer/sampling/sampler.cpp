#include "sampling/sampler.h"

#include <cmath>

#include "sampling/hash.h"

namespace rr {

namespace {

// Largest divisor of n not above √n: strata grid columns, so columns × rows = n exactly.
uint32_t gridColumnsFor(uint32_t n) {
    uint32_t c = static_cast<uint32_t>(std::sqrt(static_cast<double>(n)));
    while (c > 1 && n % c != 0)
        --c;
    return c < 1 ? 1 : c;
}

// Cranley–Patterson rotation of x ∈ [0, 1) by the offset in the top 24 bits of `bits`, in
// fixed point on the 2^-24 grid: exact modulo 1, free of branches, and the result stays in
// [0, 1). With a uniform offset the result is exactly uniform on the grid.
float rotate(float x, uint32_t bits) {
    const auto fixed = static_cast<uint32_t>(static_cast<int32_t>(x * 0x1p24f));
    return static_cast<float>((fixed + (bits >> 8)) & 0xffffffu) * 0x1p-24f;
}

// min(x, 1 − 2^-24), also mapping NaN below one.
float belowOne(float x) {
    return x < kOneMinusEpsilon ? x : kOneMinusEpsilon;
}

uint32_t high32(uint64_t h) {
    return static_cast<uint32_t>(h >> 32);
}

uint32_t repeatsOf(const DecisionSite& site) {
    return site.repeatCount < 1 ? 1 : site.repeatCount;
}

// ⌊k / d⌋ for any 32-bit k, with magic = ⌊(2^64 − 1) / d⌋ + 1 and d ≥ 2 (Lemire, Kaser &
// Kurz 2019, "Faster remainder by direct computation").
__extension__ typedef unsigned __int128 Uint128;
uint32_t divideByMagic(uint32_t k, uint64_t magic) {
    return static_cast<uint32_t>((static_cast<Uint128>(magic) * k) >> 64);
}

// Distinguish the words derived from one per-(pixel, set, decision) hash.
constexpr uint64_t kRotation2D = 0x3c6ef372fe94f82bULL;
constexpr uint64_t kJitter1D = 0xa54ff53a5f1d36f1ULL;
constexpr uint64_t kJitter2D = 0x510e527fade682d1ULL;
// Distinguishes pbrt_v1's per-sample repeat sets from the pixel's sets.
constexpr uint64_t kRepeatSet = 0x9b05688c2b3e6c1fULL;

}  // namespace

const char* samplerName(SamplerType type) {
    switch (type) {
        case SamplerType::Independent:
            return "independent";
        case SamplerType::Stratified:
            return "stratified";
        case SamplerType::Hammersley:
            return "hammersley";
        case SamplerType::PbrtV1:
            return "pbrt_v1";
    }
    return "?";
}

bool parseSamplerType(std::string_view name, SamplerType* out) {
    for (SamplerType t : {SamplerType::Independent, SamplerType::Stratified,
                          SamplerType::Hammersley, SamplerType::PbrtV1}) {
        if (name == samplerName(t)) {
            *out = t;
            return true;
        }
    }
    return false;
}

Sampler::Sampler(SamplerType type, uint32_t seed, uint32_t setSize)
    : type_(type),
      seed_(seed),
      setSize_(setSize < 1 ? 1 : setSize),
      seedKey_(mix64(uint64_t(seed) ^ 0x6a09e667f3bcc909ULL)) {
    for (uint32_t r = 1; r <= kCachedRepeatCounts; ++r) {
        shapes_[r - 1] = makeShape(setSize_ * r);
        repeatShapes_[r - 1] = makeShape(r);
    }
}

Sampler::SetShape Sampler::makeShape(uint32_t n) {
    SetShape s;
    s.size = n;
    s.columns = gridColumnsFor(n);
    s.rows = n / s.columns;
    s.invSize = 1.0f / static_cast<float>(n);
    s.invColumns = 1.0f / static_cast<float>(s.columns);
    s.invRows = 1.0f / static_cast<float>(s.rows);
    s.columnsMagic = s.columns > 1 ? UINT64_MAX / s.columns + 1 : 0;
    return s;
}

PixelSample::SetPosition PixelSample::setPosition(const DecisionSite& site, uint32_t repeatCount,
                                                  uint32_t size) const {
    // The pattern is shared by all samples of one set, for one decision site of one pixel;
    // the repeats of a site are stratified together with the set's samples. key_ already
    // hashes (seed, pixel, set): one mix adds the decision and vertex (not the repeat). The
    // low 32 bits of the result select the permutation, the high 32 bits the 1-D rotation.
    SetPosition p;
    p.key = mixKey(key_, DecisionSite{site.decision, site.vertex}.key() >> 32);
    p.index = slot_ * repeatCount + site.repeat;
    p.point = permuteIndex(p.index, size, static_cast<uint32_t>(p.key));
    return p;
}

PixelSample::SetDraw PixelSample::setDraw(const DecisionSite& site) const {
    const Sampler& s = *sampler_;
    const uint32_t repeatCount = repeatsOf(site);
    if (s.type_ == SamplerType::PbrtV1 && repeatCount > 1) {
        // This pixel sample's repeats alone: a set keyed by the sample too.
        const Sampler::SetShape shape = s.repeatShape(repeatCount);
        SetPosition p;
        p.key = mixKey(mixKey(key_, kRepeatSet + slot_),
                       DecisionSite{site.decision, site.vertex}.key() >> 32);
        p.index = site.repeat;
        p.point = permuteIndex(p.index, shape.size, static_cast<uint32_t>(p.key));
        return {shape.size,       shape.columns, shape.rows,         shape.invSize,
                shape.invColumns, shape.invRows, shape.columnsMagic, p};
    }
    const Sampler::SetShape shape = s.shape(repeatCount);
    return {shape.size,         shape.columns,
            shape.rows,         shape.invSize,
            shape.invColumns,   shape.invRows,
            shape.columnsMagic, setPosition(site, repeatCount, shape.size)};
}

float PixelSample::get1D(const DecisionSite& site) const {
    const Sampler& s = *sampler_;
    if (s.type_ == SamplerType::Independent)
        return toUnitFloat(pcgOutput(mixKey(key_, site.key())));

    const SetDraw shape = setDraw(site);
    const auto [key, j, k] = shape.position;
    float x;
    if (s.type_ != SamplerType::Hammersley) {
        const float jitter = toUnitFloat(high32(mixKey(key ^ kJitter1D, j)));
        x = (static_cast<float>(k) + jitter) * shape.invSize;
    } else {
        x = static_cast<float>(k) * shape.invSize;  // Hammersley's first coordinate
    }
    return rotate(belowOne(x), high32(key));
}

Vec2 PixelSample::get2D(const DecisionSite& site) const {
    const Sampler& s = *sampler_;
    if (s.type_ == SamplerType::Independent) {
        // Two consecutive outputs of a PCG generator seeded with the hash.
        const uint64_t h = mixKey(key_, site.key());
        return {toUnitFloat(pcgOutput(h)), toUnitFloat(pcgOutput(pcgStep(h)))};
    }

    const SetDraw shape = setDraw(site);
    const auto [key, j, k] = shape.position;
    Vec2 p;
    if (s.type_ != SamplerType::Hammersley) {
        const uint32_t row = shape.columns > 1 ? divideByMagic(k, shape.columnsMagic) : k;
        const uint32_t column = k - row * shape.columns;
        const uint64_t jitter = mixKey(key ^ kJitter2D, j);
        p.x = (static_cast<float>(column) + toUnitFloat(high32(jitter))) * shape.invColumns;
        p.y =
            (static_cast<float>(row) + toUnitFloat(static_cast<uint32_t>(jitter))) * shape.invRows;
    } else {
        p.x = static_cast<float>(k) * shape.invSize;
        p.y = radicalInverseBase2(k);
    }
    const uint64_t rotation = mix64(key ^ kRotation2D);
    return {rotate(belowOne(p.x), high32(rotation)),
            rotate(belowOne(p.y), static_cast<uint32_t>(rotation))};
}

}  // namespace rr
