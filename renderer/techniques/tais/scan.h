// TAIS's importance propagation (Cline et al. 2008, §3.3, fig. 3). Pixels are rendered in the
// serpentine order of render/scan_bands.h, and each pixel starts from the average of the maps
// of its already-rendered neighbours, of which only two rows are kept in memory.
//
// The paper's figure 3 is not in its text; we read its seven neighbours as the five pixels
// x−2 … x+2 of the row above and the two pixels before this one in the current row's scan
// direction (all already rendered under a serpentine scan), clipped at the image edges. A band
// starts on the warm-up rows it scans from the band above (ScanBands), so its first row of kept
// pixels already has neighbours above it.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace rr::tais {

struct PixelCoord {
    int x = 0, y = 0;
    bool operator==(const PixelCoord&) const = default;
};

// The already-rendered neighbours of pixel x in row `rowInBand` of a band (see above).
std::vector<PixelCoord> renderedNeighbours(int x, int rowInBand, int width);

// The maps of two rows of a band: the row being rendered and the one above it. `Maps` is a
// pixel's set of importance maps: copyable, with accumulate(other) and scale(factor).
template <class Maps>
class MapRows {
  public:
    // `initial`: the maps of a pixel with no rendered neighbour (uniform). Every slot holds a
    // copy from the start, so storing and averaging reuse their memory pixel after pixel.
    MapRows(int width, Maps initial)
        : width_(width),
          initial_(std::move(initial)),
          above_(width, initial_),
          current_(width, initial_) {}

    // Fig. 3: the sum of the maps of the pixel's rendered neighbours (the initial maps for
    // the band's first pixel) into *out; returns how many were summed (at least 1).
    int neighbourSum(int x, int rowInBand, Maps* out) const {
        const std::vector<PixelCoord> neighbours = renderedNeighbours(x, rowInBand, width_);
        if (neighbours.empty()) {
            *out = initial_;
            return 1;
        }
        *out = mapsAt(neighbours.front(), rowInBand);
        for (size_t i = 1; i < neighbours.size(); ++i)
            out->accumulate(mapsAt(neighbours[i], rowInBand));
        return int(neighbours.size());
    }
    // The pixel's maps once it is rendered (Algorithm 1, line 24). They are swapped into the
    // row, so *maps is left holding stale maps whose memory the next pixel reuses.
    void store(int x, Maps* maps) { std::swap(current_[size_t(x)], *maps); }
    // Moves on to the next row: the current row becomes the row above.
    void nextRow() { above_.swap(current_); }

  private:
    const Maps& mapsAt(const PixelCoord& p, int rowInBand) const {
        return (p.y == rowInBand ? current_ : above_)[size_t(p.x)];
    }

    int width_;
    Maps initial_;
    std::vector<Maps> above_, current_;
};

}  // namespace rr::tais
