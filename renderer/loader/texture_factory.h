// Material parameters from JSON: a number or [r, g, b] is a constant; an object with a "type"
// is a texture (see configs/README.md, "Textures"). `range` bounds every value the texture
// can take, so a texture can never hand a material an impossible parameter: constants and
// the endpoints of checkers and gradients are checked as they are read, image texels (times
// the image's scale) when the image is loaded. Interpolation (gradients, bilinear lookups)
// forms convex combinations, which stay within the range.
#pragma once

#include <string>

#include "config/json_reader.h"
#include "loader/asset_resolver.h"
#include "scene/checkerboard.h"
#include "scene/texture.h"

namespace rr {

TexturePtr<float> readFloatTexture(ObjectReader& json, const std::string& key, float fallback,
                                   Range range, const AssetResolver& assets);
TexturePtr<Rgb> readRgbTexture(ObjectReader& json, const std::string& key, const Rgb& fallback,
                               Range range, const AssetResolver& assets);

// "squares": [nu, nv], integers ≥ 1, default [8, 8] (checker textures and materials).
Checkerboard readCheckerboard(ObjectReader& json);

}  // namespace rr
