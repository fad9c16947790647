// Spatially varying material parameters. A texture maps a shading point (uv, position) to a
// value; materials hold their parameters as textures, so any parameter may be a constant, a
// checkerboard, a gradient or an image. Textures are immutable and may be shared.
#pragma once

#include <memory>

#include "math/rgb.h"
#include "scene/shading_context.h"

namespace rr {

template <class T>
class Texture {
  public:
    virtual ~Texture() = default;
    virtual T eval(const ShadingContext& ctx) const = 0;
};

using FloatTexture = Texture<float>;
using RgbTexture = Texture<Rgb>;
template <class T>
using TexturePtr = std::shared_ptr<const Texture<T>>;

template <class T>
class ConstantTexture final : public Texture<T> {
  public:
    explicit ConstantTexture(const T& value) : value_(value) {}
    T eval(const ShadingContext&) const override { return value_; }
    const T& value() const { return value_; }

  private:
    T value_;
};

template <class T>
TexturePtr<T> constantTexture(const T& value) {
    return std::make_shared<ConstantTexture<T>>(value);
}

// The value of a constant texture, or nullptr when the texture varies: for load-time checks
// of combinations of parameters (Phong's kd + ks ≤ 1) that only constants allow.
template <class T>
const T* constantValue(const TexturePtr<T>& texture) {
    const auto* constant = dynamic_cast<const ConstantTexture<T>*>(texture.get());
    return constant ? &constant->value() : nullptr;
}

}  // namespace rr
