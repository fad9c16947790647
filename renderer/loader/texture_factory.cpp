#include "loader/texture_factory.h"

namespace rr {

TexturePtr<float> readFloatTexture(ObjectReader& json, const std::string& key, float fallback,
                                   Range range, const AssetResolver&) {
    if (const Json* value = json.rawOptional(key); value && value->is_object())
        json.fail(key, "texture objects are not supported yet");
    return constantTexture(json.getFloat(key, fallback, range));
}

TexturePtr<Rgb> readRgbTexture(ObjectReader& json, const std::string& key, const Rgb& fallback,
                               Range range, const AssetResolver&) {
    if (const Json* value = json.rawOptional(key); value && value->is_object())
        json.fail(key, "texture objects are not supported yet");
    return constantTexture(json.getRgb(key, fallback, range));
}

}  // namespace rr
