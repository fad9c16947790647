// Counter-based random numbers: a value is a pure function of its integer coordinates, so the
// same (pixel, sample, dimension, seed) gives the same number on any thread, in any order.
#pragma once

#include <cstdint>

namespace rr {

// MurmurHash3's 64-bit finaliser: a bijective avalanche mix.
constexpr uint64_t mix64(uint64_t k) {
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdULL;
    k ^= k >> 33;
    k *= 0xc4ceb9fe1a85ec53ULL;
    k ^= k >> 33;
    return k;
}

// Order-dependent combination of several integer keys.
constexpr uint64_t hashKeys(uint64_t a, uint64_t b) {
    return mix64(a ^ (mix64(b) + 0x9e3779b97f4a7c15ULL + (a << 6) + (a >> 2)));
}
constexpr uint64_t hashKeys(uint64_t a, uint64_t b, uint64_t c) {
    return hashKeys(hashKeys(a, b), c);
}
constexpr uint64_t hashKeys(uint64_t a, uint64_t b, uint64_t c, uint64_t d) {
    return hashKeys(hashKeys(a, b, c), d);
}

// One avalanche mix of a (well-mixed) base key with a small integer key: SplitMix64's
// construction (Steele, Lea & Flood 2014), which spreads `k` with an odd Weyl constant before
// the finaliser. Much cheaper than hashKeys() and as good when `base` is already a hash.
constexpr uint64_t mixKey(uint64_t base, uint64_t k) {
    return mix64(base + k * 0x9e3779b97f4a7c15ULL);
}

// The next state of PCG's 64-bit LCG: pcgOutput(state) and pcgOutput(pcgStep(state)) are two
// consecutive outputs of a PCG generator seeded with `state`.
constexpr uint64_t pcgStep(uint64_t state) {
    return state * 6364136223846793005ULL + 1442695040888963407ULL;
}

// PCG's RXS-M-XS output permutation (O'Neill 2014) applied to a hashed state: the
// "hashed PCG" generator, 32 well-mixed bits per coordinate.
constexpr uint32_t pcgOutput(uint64_t state) {
    const uint64_t word = ((state >> ((state >> 59u) + 5u)) ^ state) * 12605985483714917081ULL;
    return static_cast<uint32_t>((word >> 43u) ^ (word >> 11u));
}

// Uniform float in [0, 1) from the top 24 bits (exactly representable, never 1).
constexpr float toUnitFloat(uint32_t bits) {
    return static_cast<float>(bits >> 8) * 0x1p-24f;
}

// Kensler's hashed permutation (Correlated Multi-Jittered Sampling, 2013): maps i ∈ [0, n) to
// a pseudo-random permutation of [0, n) selected by `key`, without storing the permutation.
uint32_t permuteIndex(uint32_t i, uint32_t n, uint32_t key);

// Van der Corput radical inverse in base 2, as a float in [0, 1).
constexpr float radicalInverseBase2(uint32_t i) {
    i = (i << 16u) | (i >> 16u);
    i = ((i & 0x00ff00ffu) << 8u) | ((i & 0xff00ff00u) >> 8u);
    i = ((i & 0x0f0f0f0fu) << 4u) | ((i & 0xf0f0f0f0u) >> 4u);
    i = ((i & 0x33333333u) << 2u) | ((i & 0xccccccccu) >> 2u);
    i = ((i & 0x55555555u) << 1u) | ((i & 0xaaaaaaaau) >> 1u);
    return toUnitFloat(i);
}

}  // namespace rr
