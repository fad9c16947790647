// Turns a finished film into the EXR the renderer writes. Channel names (documented in
// configs/README.md):
//   R, G, B                      the pixel's estimate: the mean of its samples, or the
//                                integrator's own estimates when it gives them (PMC-IP)
//   variance.R/.G/.B             that estimate's variance (for a mean of samples, their
//                                variance / their number)
//   samples                      number of samples in the pixel
#pragma once

#include <vector>

#include "integrators/integrator.h"
#include "io/exr_io.h"
#include "render/film.h"

namespace rr {

// `estimates`: pixel estimates and their variances replacing the samples' means and the
// variances of those, or empty.
ExrImage filmToExr(const Film& film, const PixelEstimates& estimates = {});

}  // namespace rr
