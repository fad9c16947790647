#include "support/mean_agreement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rr::test {

namespace {

struct Region {
    int x0, y0, x1, y1;
};

std::vector<Region> imageAndBlocks(int width, int height, int block) {
    std::vector<Region> r{{0, 0, width, height}};
    for (int y = 0; y < height; y += block)
        for (int x = 0; x < width; x += block)
            r.push_back({x, y, std::min(x + block, width), std::min(y + block, height)});
    return r;
}

// The mean over seeds of a region's mean, with its standard error.
Estimate meanOverSeeds(const std::vector<TestRender>& renders, int c, const Region& r) {
    double sum = 0, variance = 0;
    for (const TestRender& render : renders) {
        const Estimate e = regionMean(render.film, c, r.x0, r.y0, r.x1, r.y1);
        sum += e.mean;
        variance += e.standardError * e.standardError;
    }
    const double n = double(renders.size());
    return {sum / n, std::sqrt(variance) / n};
}

}  // namespace

int regionTests(int width, int height, int block) {
    return 3 * int(imageAndBlocks(width, height, block).size());
}

Disagreement largestDisagreement(const std::vector<TestRender>& renders, const Film& reference,
                                 int block, const std::string& label) {
    Disagreement worst;
    for (const Region& r : imageAndBlocks(reference.width(), reference.height(), block))
        for (int c = 0; c < 3; ++c) {
            const Estimate a = meanOverSeeds(renders, c, r);
            const Estimate b = regionMean(reference, c, r.x0, r.y0, r.x1, r.y1);
            const double se = std::hypot(a.standardError, b.standardError);
            const double z = se > 0 ? std::abs(a.mean - b.mean) / se : (a.mean == b.mean ? 0 : 1e9);
            if (z <= worst.z) continue;
            worst.z = z;
            worst.where = "channel " + std::to_string(c) + ", pixels [" + std::to_string(r.x0) +
                          "," + std::to_string(r.x1) + ")×[" + std::to_string(r.y0) + "," +
                          std::to_string(r.y1) + "): " + label + " " + std::to_string(a.mean) +
                          " ± " + std::to_string(a.standardError) + ", reference " +
                          std::to_string(b.mean) + " ± " + std::to_string(b.standardError);
        }
    return worst;
}

void expectImageMeansAgreePairwise(const std::vector<TestRender>& renders,
                                   const std::vector<std::string>& names, double threshold,
                                   const std::string& what) {
    for (size_t i = 0; i < renders.size(); ++i)
        for (size_t j = i + 1; j < renders.size(); ++j)
            for (int c = 0; c < 3; ++c) {
                const Estimate a = imageMean(renders[i].film, c);
                const Estimate b = imageMean(renders[j].film, c);
                const double z = (a.mean - b.mean) / std::hypot(a.standardError, b.standardError);
                EXPECT_LT(std::abs(z), threshold)
                    << what << ": " << names[i] << " vs " << names[j] << ", channel " << c
                    << ": " << a.mean << " ± " << a.standardError << " vs " << b.mean << " ± "
                    << b.standardError;
            }
}

}  // namespace rr::test
