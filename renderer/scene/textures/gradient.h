// Linear ramp from one value to another along a texture coordinate: `from` at 0, `to` at 1,
// clamped outside [0, 1] so the values stay between the two endpoints.
#pragma once

#include "math/vector.h"
#include "scene/texture.h"

namespace rr {

template <class T>
class GradientTexture final : public Texture<T> {
  public:
    enum class Axis { U, V };

    GradientTexture(const T& from, const T& to, Axis axis) : from_(from), to_(to), axis_(axis) {}

    T eval(const ShadingContext& ctx) const override {
        const float t = clamp(axis_ == Axis::U ? ctx.uv.x : ctx.uv.y, 0.0f, 1.0f);
        return from_ * (1.0f - t) + to_ * t;  // a convex combination: never outside the ends
    }

  private:
    T from_, to_;
    Axis axis_;
};

}  // namespace rr
