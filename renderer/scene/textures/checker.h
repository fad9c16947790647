// Checkerboard of two textures (which may themselves vary): "even" squares take one, "odd"
// squares the other (scene/checkerboard.h).
#pragma once

#include "scene/checkerboard.h"
#include "scene/texture.h"

namespace rr {

template <class T>
class CheckerTexture final : public Texture<T> {
  public:
    CheckerTexture(TexturePtr<T> even, TexturePtr<T> odd, Checkerboard board)
        : even_(std::move(even)), odd_(std::move(odd)), board_(board) {}

    T eval(const ShadingContext& ctx) const override {
        return board_.isEven(ctx.uv) ? even_->eval(ctx) : odd_->eval(ctx);
    }

  private:
    TexturePtr<T> even_, odd_;
    Checkerboard board_;
};

}  // namespace rr
