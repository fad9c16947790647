#include "loader/asset_files.h"

namespace rr {

std::filesystem::path readAssetPath(ObjectReader& json, const std::string& key,
                                    const AssetResolver& assets, const std::string& what) {
    const std::string file = json.getString(key);
    const auto path = assets.resolve(file);
    if (!path)
        throw ConfigError(json.pointerTo(key),
                          what + " \"" + file + "\" not found; searched " + assets.describe() +
                              " (run `make assets`, or put the file under assets/ or set "
                              "RENDERER_ASSETS)",
                          ConfigError::Kind::MissingAsset);
    return *path;
}

RgbImage readImageAsset(ObjectReader& json, const std::string& key, const AssetResolver& assets,
                        const std::string& what) {
    const std::filesystem::path path = readAssetPath(json, key, assets, what);
    RgbImage image;
    try {
        image = readRgbImage(path);
    } catch (const std::exception& e) {
        json.fail(key, e.what());
    }
    // Texels are radiance or reflectance: a negative one means nothing either.
    for (const Rgb& p : image.pixels)
        if (!p.isFinite() || p.r < 0 || p.g < 0 || p.b < 0)
            json.fail(key, path.string() + " holds negative or non-finite values");
    return image;
}

}  // namespace rr
