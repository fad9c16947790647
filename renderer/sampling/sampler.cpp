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

float wrap(float x) {
    return x >= 1.0f ? x - 1.0f : x;
}

// Cranley–Patterson rotation; the result stays in [0, 1).
float rotate(float x, uint64_t key) {
    const float r = wrap(x + toUnitFloat(pcgOutput(key)));
    return r < 1.0f ? r : 0x1.fffffep-1f;
}

}  // namespace

const char* samplerName(SamplerType type) {
    switch (type) {
        case SamplerType::Independent:
            return "independent";
        case SamplerType::Stratified:
            return "stratified";
        case SamplerType::Hammersley:
            return "hammersley";
    }
    return "?";
}

bool parseSamplerType(std::string_view name, SamplerType* out) {
    for (SamplerType t :
         {SamplerType::Independent, SamplerType::Stratified, SamplerType::Hammersley}) {
        if (name == samplerName(t)) {
            *out = t;
            return true;
        }
    }
    return false;
}

Sampler::Sampler(SamplerType type, uint32_t seed, uint32_t setSize)
    : type_(type), seed_(seed), setSize_(setSize < 1 ? 1 : setSize) {
    gridColumns_ = gridColumnsFor(setSize_);
}

PixelSample::SetPosition PixelSample::setPosition(const DecisionSite& site) const {
    // The pattern is shared by all samples of one set, for one decision site of one pixel;
    // the repeats of a site are stratified together with the set's samples.
    const Sampler& s = *sampler_;
    SetPosition p;
    const uint32_t set = sample_ / s.setSize_;
    p.key = hashKeys(s.seed_, pixel_, set, DecisionSite{site.decision, site.vertex}.key());
    p.size = s.setSize_ * site.repeatCount;
    p.index = (sample_ % s.setSize_) * site.repeatCount + site.repeat;
    p.point = permuteIndex(p.index, p.size, static_cast<uint32_t>(p.key));
    return p;
}

float PixelSample::get1D(const DecisionSite& site) const {
    const Sampler& s = *sampler_;
    if (s.type_ == SamplerType::Independent)
        return toUnitFloat(pcgOutput(hashKeys(s.seed_, pixel_, sample_, site.key())));

    const auto [key, n, j, k] = setPosition(site);
    float x;
    if (s.type_ == SamplerType::Stratified) {
        const float jitter = toUnitFloat(pcgOutput(hashKeys(key, j, 1)));
        x = (static_cast<float>(k) + jitter) / static_cast<float>(n);
    } else {
        x = static_cast<float>(k) / static_cast<float>(n);  // Hammersley's first coordinate
    }
    return rotate(x < 1.0f ? x : 0x1.fffffep-1f, key ^ 0x51ed270b);
}

Vec2 PixelSample::get2D(const DecisionSite& site) const {
    const Sampler& s = *sampler_;
    if (s.type_ == SamplerType::Independent) {
        const uint64_t h = hashKeys(s.seed_, pixel_, sample_, site.key());
        return {toUnitFloat(pcgOutput(h)), toUnitFloat(pcgOutput(mix64(h + 1)))};
    }

    const auto [key, n, j, k] = setPosition(site);
    Vec2 p;
    if (s.type_ == SamplerType::Stratified) {
        const uint32_t cols = site.repeatCount == 1 ? s.gridColumns_ : gridColumnsFor(n);
        const uint32_t rows = n / cols;
        const uint64_t jitterKey = hashKeys(key, j, 2);
        p.x = (static_cast<float>(k % cols) + toUnitFloat(pcgOutput(jitterKey))) / cols;
        p.y = (static_cast<float>(k / cols) + toUnitFloat(pcgOutput(mix64(jitterKey)))) / rows;
    } else {
        p.x = static_cast<float>(k) / static_cast<float>(n);
        p.y = radicalInverseBase2(k);
    }
    p.x = std::min(p.x, 0x1.fffffep-1f);
    p.y = std::min(p.y, 0x1.fffffep-1f);
    return {rotate(p.x, key ^ 0x2545f491), rotate(p.y, key ^ 0x9e3779b9)};
}

}  // namespace rr
