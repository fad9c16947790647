// Material parameters from JSON: a number or [r, g, b] is a constant; an object with a "type"
// is a texture (see configs/README.md, "Textures"). `range` bounds every value the texture
// can take, so a texture can never hand a material an impossible parameter: constants and
// the endpoints of checkers and gradients are checked as they are read, image texels (times
// the image's scale) when the image is loaded. Interpolation (gradients, bilinear lookups)
// forms convex combinations, which stay within the range.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "config/json_reader.h"
#include "loader/asset_resolver.h"
#include "scene/checkerboard.h"
#include "scene/texture.h"

namespace rr {

// The texture-valued key `key`, with the range and default its table declares (a
// NumberTexture or ColourTexture key).
TexturePtr<float> readFloatTexture(ObjectReader& json, const std::string& key,
                                   const AssetResolver& assets);
TexturePtr<Rgb> readRgbTexture(ObjectReader& json, const std::string& key,
                               const AssetResolver& assets);
// The same with a default that depends on other keys (the table says so in words).
TexturePtr<Rgb> readRgbTexture(ObjectReader& json, const std::string& key, const Rgb& fallback,
                               const AssetResolver& assets);

// "squares": [nu, nv], integers ≥ 1, default [8, 8] (checker textures and materials): its
// declaration, for their tables, and its reading.
KeySpec squaresKey();
Checkerboard readCheckerboard(ObjectReader& json);

// Each texture type's keys.
std::vector<std::pair<std::string, const KeyTable*>> textureTypeKeys();

}  // namespace rr
