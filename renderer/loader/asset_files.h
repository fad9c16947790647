// Reading the files a scene names (meshes, images, environment maps) from the asset search
// path, with the errors every such key shares: a missing file names itself and every
// directory searched; an unreadable one names the reason; both at the key's JSON pointer.
#pragma once

#include <filesystem>
#include <string>

#include "config/json_reader.h"
#include "io/rgb_image_io.h"
#include "loader/asset_resolver.h"

namespace rr {

// The file named by the string at `key`; `what` says what it is ("mesh", "image", ...).
std::filesystem::path readAssetPath(ObjectReader& json, const std::string& key,
                                    const AssetResolver& assets, const std::string& what);

// The image named by the string at `key` (EXR or Radiance .hdr), with finite values.
RgbImage readImageAsset(ObjectReader& json, const std::string& key, const AssetResolver& assets,
                        const std::string& what);

}  // namespace rr
