// Resampling an environment image into the latitude-longitude layout, once at load: techniques
// that work on the lat-long grid (two-stage sampling's summed-area table and partition) need
// the map in that form, and the light every technique sees must then be this resampled map, so
// that the scene's radiance and the technique's density are built on the same texels.
#pragma once

#include "io/rgb_image_io.h"
#include "scene/lights/env_layout.h"

namespace rr {

// A `width` × `width`/2 lat-long image of `image` (laid out by `from`): each texel the mean of
// 2 × 2 nearest-texel lookups at its sub-texel centres. Texels of `image` whose centre has no
// solid angle (the probe's outside, which holds the copyright notice) read as black, as the
// EnvironmentMap masks them.
RgbImage resampleToLatLong(const RgbImage& image, const EnvLayout& from, int width);

}  // namespace rr
