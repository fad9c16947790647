#include "techniques/tais/scan.h"

namespace rr::tais {

namespace {

// The row's scan direction (render/scan_bands.h): +1 for the band's even rows, −1 for its odd
// ones.
int direction(int rowInBand) {
    return rowInBand % 2 == 0 ? 1 : -1;
}

}  // namespace

std::vector<PixelCoord> renderedNeighbours(int x, int rowInBand, int width) {
    std::vector<PixelCoord> neighbours;
    if (rowInBand > 0)
        for (int dx = -2; dx <= 2; ++dx)
            if (x + dx >= 0 && x + dx < width) neighbours.push_back({x + dx, rowInBand - 1});
    const int back = -direction(rowInBand);  // towards the pixels already rendered
    for (int k = 1; k <= 2; ++k)
        if (x + back * k >= 0 && x + back * k < width)
            neighbours.push_back({x + back * k, rowInBand});
    return neighbours;
}

}  // namespace rr::tais
