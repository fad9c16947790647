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

}  // namespace rr::test
