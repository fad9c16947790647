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

#include <algorithm>
#include <array>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

namespace rr::tais {

// The scan direction of a band's row (render/scan_bands.h): +1 for its even rows, −1 for its
// odd ones.
inline int scanDirection(int rowInBand) {
    return rowInBand % 2 == 0 ? 1 : -1;
}

// The maps of two rows of a band: the row being rendered and the one above it. `Maps` is a
// pixel's set of importance maps: copyable, with assignSum(parts, normalize) and
// slide(entering, leaving) (PixelMaps, InvertedMap1D).
template <class Maps>
class MapRows {
  public:
    // Fig. 3: the maps whose sum is the pixel's rendered neighbours' (the initial maps alone
    // for the band's first pixel): the running sum over the row above, then up to two pixels
    // before this one in the row; `count` neighbours in all (at least 1).
    struct Neighbours {
        std::array<const Maps*, 3> parts;
        int partCount = 0;
        int count = 0;
        std::span<const Maps* const> list() const { return {parts.data(), size_t(partCount)}; }
    };

    // `initial`: the maps of a pixel with no rendered neighbour (uniform). Every slot holds a
    // copy from the start, so storing and summing reuse their memory pixel after pixel.
    MapRows(int width, Maps initial)
        : width_(width),
          initial_(std::move(initial)),
          above_(width, initial_),
          current_(width, initial_),
          window_(initial_) {}

    // The five pixels above are a window that moves one pixel per call along the row: it is
    // kept as a running sum, the pixel entering added and the one leaving subtracted, and
    // summed afresh where the scan jumps (a new row, or a call out of order). The parts stay
    // valid until the next call or store().
    Neighbours neighbours(int x, int rowInBand) {
        Neighbours n;
        if (rowInBand > 0) {
            n.count = slideWindow(x, rowInBand);
            n.parts[size_t(n.partCount++)] = &window_;
        }
        const int back = -scanDirection(rowInBand);  // towards the pixels already rendered
        for (int k = 1; k <= 2; ++k) {
            const int left = x + back * k;
            if (!inside(left)) continue;
            n.parts[size_t(n.partCount++)] = &current_[size_t(left)];
            ++n.count;
        }
        if (n.count == 0) {
            n.parts[0] = &initial_;
            n.partCount = n.count = 1;
        }
        return n;
    }
    // The pixel's maps once it is rendered (Algorithm 1, line 24). They are swapped into the
    // row, so *maps is left holding stale maps whose memory the next pixel reuses.
    void store(int x, Maps* maps) { std::swap(current_[size_t(x)], *maps); }
    // Moves on to the next row: the current row becomes the row above.
    void nextRow() {
        above_.swap(current_);
        windowRow_ = -1;
    }

  private:
    bool inside(int x) const { return x >= 0 && x < width_; }

    // window_ = the maps of pixels x − 2 … x + 2 of the row above (clipped); returns how many.
    int slideWindow(int x, int rowInBand) {
        const int d = scanDirection(rowInBand);
        if (rowInBand == windowRow_ && x == windowX_ + d) {
            const int entering = x + 2 * d, leaving = x - 3 * d;
            window_.slide(inside(entering) ? &above_[size_t(entering)] : nullptr,
                          inside(leaving) ? &above_[size_t(leaving)] : nullptr);
        } else {
            std::array<const Maps*, 5> parts;
            size_t count = 0;
            for (int dx = -2; dx <= 2; ++dx)
                if (inside(x + dx)) parts[count++] = &above_[size_t(x + dx)];
            window_.assignSum(std::span<const Maps* const>(parts.data(), count), false);
        }
        windowRow_ = rowInBand;
        windowX_ = x;
        return std::min(x + 2, width_ - 1) - std::max(x - 2, 0) + 1;
    }

    int width_;
    Maps initial_;
    std::vector<Maps> above_, current_;
    Maps window_;  // the running sum over the row above (slideWindow)
    int windowRow_ = -1, windowX_ = 0;
};

}  // namespace rr::tais
