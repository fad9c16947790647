// Turns a finished film into the EXR the renderer writes. Channel names (documented in
// configs/README.md):
//   R, G, B                      mean radiance of the pixel
//   variance.R/.G/.B             variance of that mean (sample variance / samples)
//   samples                      number of samples in the pixel
#pragma once

#include "io/exr_io.h"
#include "render/film.h"

namespace rr {

ExrImage filmToExr(const Film& film);

}  // namespace rr
