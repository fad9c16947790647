// Threshold-versus-intensity functions of Ferwerda et al. 1996 ("A model of visual adaptation
// for realistic image synthesis"): the smallest visible luminance difference against an
// adapting luminance, both in cd/m².
#pragma once

namespace rr {

// The tvi error needs absolute luminance: by default pixel value 1 is displayed as a
// 100 cd/m² white (the metrics tool's default; PMC-IP adapts on the same scale).
inline constexpr double kDefaultCdPerUnit = 100;

// Cone (photopic) threshold; the one the tvi error of Lai et al. 2007 uses.
double photopicTvi(double adaptingLuminance);
// Rod (scotopic) threshold, for completeness; no metric uses it.
double scotopicTvi(double adaptingLuminance);

}  // namespace rr
