// Maximum contribution filtering (Cline et al. 2008, §3.4, eq. 4): after a pixel is rendered,
// each sample's brightness s_i is clamped to m_i = (s − s_i) · max(32/n, 0.02), where s is the
// sum of the pixel's sample brightnesses and n the number of samples. It removes the spikes of
// newly discovered bright paths at the cost of bias (darkening where a few bright samples
// dominate), so it is an option and its results are reported apart from the unbiased ones.
#pragma once

#include <span>

#include "math/rgb.h"

namespace rr::tais {

// Clamps the samples in place (colour scaled so that its luminance, the brightness, is at
// most m_i) and returns how many were clamped. The limits use the brightnesses before any
// clamping.
int filterMaximumContribution(std::span<Rgb> samples);

}  // namespace rr::tais
