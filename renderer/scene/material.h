// Material (BSDF) interface, in the local shading frame where the normal is +z.
//  - eval(wo, wi): f(wo, wi)·|cos θi|, zero for specular lobes;
//  - pdf(wo, wi): solid-angle density of sample(); zero for specular lobes;
//  - sample(): picks a lobe with `uLobe` (a named decision, which a technique may replace) and
//    a direction with `uDirection`, returns weight = f·|cos θi| / pdf.
// What only some estimators ask of a material is a capability it may also implement
// (scene/lobe_peaks.h).
// Materials without transmission are two-sided: they mirror wo to the normal's side.
#pragma once

#include <cstdint>

#include "math/rgb.h"
#include "math/vector.h"
#include "scene/shading_context.h"

namespace rr {

enum LobeFlags : uint8_t {
    kReflection = 1 << 0,
    kTransmission = 1 << 1,
    kDiffuse = 1 << 2,
    kGlossy = 1 << 3,
    kSpecular = 1 << 4,
};

struct BsdfSample {
    Vec3 wi;        // local frame
    Rgb weight;     // f·|cos θi| / pdf (for specular lobes: the lobe's value / its probability)
    float pdf = 0;  // solid angle; for specular lobes the discrete probability of the lobe
    float eta = 1;  // ηt/ηi across the interface for transmission, 1 otherwise
    uint8_t lobe = 0;
    bool isSpecular() const { return (lobe & kSpecular) != 0; }
};

class Material {
  public:
    virtual ~Material() = default;

    virtual Rgb eval(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const = 0;
    virtual float pdf(const ShadingContext& ctx, const Vec3& wo, const Vec3& wi) const = 0;
    virtual bool sample(const ShadingContext& ctx, const Vec3& wo, float uLobe, Vec2 uDirection,
                        BsdfSample* out) const = 0;

    // Materials that both reflect and transmit (glass) choose between the two with uLobe:
    // sample() reflects exactly when uLobe < reflectionChoice(ctx, wo), and the sample's pdf
    // is that probability (or its complement), which a technique that steers the choice
    // re-weights.
    virtual float reflectionChoice(const ShadingContext& /*ctx*/, const Vec3& /*wo*/) const {
        return 1;
    }

    // Union of the lobes this material can produce.
    virtual uint8_t lobes() const = 0;
    bool hasNonSpecular() const { return (lobes() & (kDiffuse | kGlossy)) != 0; }
    // Materials with transmission need true orientation (entering vs leaving).
    bool hasTransmission() const { return (lobes() & kTransmission) != 0; }

    // Index in the scene's material list; set by the scene.
    int index() const { return index_; }
    void setIndex(int i) { index_ = i; }

  private:
    int index_ = -1;
};

}  // namespace rr
