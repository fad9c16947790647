// Unbiasedness by z-tests: the mean over independent renders (seeds) of a technique against a
// long reference render, for the image mean and every block mean of every channel. Standard
// errors come from the per-pixel sample variances (scene_testing.h).
#pragma once

#include <string>
#include <vector>

#include "support/scene_testing.h"

namespace rr::test {

// Tests one comparison makes on a width × height image cut into block × block blocks.
int regionTests(int width, int height, int block);

// The largest |z| over all regions and channels, and where.
struct Disagreement {
    double z = 0;
    std::string where;
};

// `label` names the technique in the description of the worst region.
Disagreement largestDisagreement(const std::vector<TestRender>& renders, const Film& reference,
                                 int block, const std::string& label);

// Independent estimates of one image (renders[i] named names[i]) agree pairwise: each
// channel's image mean, by |z| < `threshold` (the caller's Šidák-corrected level over
// pairs × 3 channels). Failures name the pair, the channel and both estimates, after `what`.
void expectImageMeansAgreePairwise(const std::vector<TestRender>& renders,
                                   const std::vector<std::string>& names, double threshold,
                                   const std::string& what);

}  // namespace rr::test
