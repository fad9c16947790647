// Turns a finished film into the EXR the renderer writes. Channel names (documented in
// configs/README.md):
//   R, G, B                      the pixel's estimate: the mean of its samples, or the
//                                integrator's own estimates when it gives them (PMC-IP)
//   variance.R/.G/.B             variance of the samples' mean (sample variance / samples)
//   samples                      number of samples in the pixel
#pragma once

#include <vector>

#include "io/exr_io.h"
#include "render/film.h"

namespace rr {

// `estimates`: row-major pixel estimates replacing the samples' means, or empty.
ExrImage filmToExr(const Film& film, const std::vector<Rgb>& estimates = {});

}  // namespace rr
