// Sampling an image's texels with probability ∝ weight, laid out so that draws stay in cache: an
// environment map of a million texels is sampled for every light sample, and resampling draws
// many light samples per shading point (RIS issue 40: a row-then-column CDF over the whole image
// costs three to four cache misses a draw, 400 ns on Galileo's probe).
//
// Two levels, each the standard two-step inversion (Pharr et al., "Physically Based Rendering",
// §13.6.7: a row from the marginal, then a cell of the row from its conditional):
//  1. a block of 8 × 8 texels, from the image coarsened to blocks: a row of blocks from their
//     marginal, then a block of the row from its float CDF (a guide table starts the search:
//     Chen & Asau 1974), and one of the block's rows from its 8 CDF values (KBs that stay in
//     cache);
//  2. a texel of that row from the row's record: 128 bytes that hold its 8 CDF values and its 8
//     texels' values.
// A draw's memory reads thus follow the weights: bright blocks are drawn often and stay cached,
// where a one-level guide table or alias table indexes its entries uniformly in u and misses on
// almost every draw (Mitsuba 3's hierarchical 2-D warp makes the same trade with more levels).
// The block records are 40 bytes a block and the row records megabyte-scale in all; sample()'s
// steps let a caller drawing many samples fetch them for all its draws at once. A texel's density
// is computed from the intervals the draw read, not stored. Each level is monotone in each
// coordinate, so stratified u give stratified texels, and the whole map is invertible (TAIS's
// point-on-light maps index light samples by u).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "math/rgb.h"
#include "math/vector.h"
#include "sampling/distribution1d.h"
#include "sampling/huge_page_allocator.h"

namespace rr {

class TexelSampler {
  public:
    // What a draw found: the point of [0,1)² (x to the right, y down the rows), its texel, the
    // density per unit area of the square there, and the texel's value.
    struct Draw {
        Vec2 point;
        int column, row;
        float density;
        Rgb value;
    };

    TexelSampler() = default;
    // `weights` and `values`: width·height texels, row-major; weights finite and non-negative
    // (all zero: uniform).
    TexelSampler(std::span<const float> weights, std::span<const Rgb> values, int width,
                 int height);

    // Where a draw stands: what the next step needs.
    struct Ticket {
        float ux, uy;                    // u.x; u.y remapped within the row of blocks
        int blockColumn, blockRow, row;  // row: within the block
        float v;                         // u.y remapped within the texel row
    };

    // False only for a texel of zero density, which the search never selects.
    bool sample(Vec2 u, Draw* out) const {
        Ticket ticket;
        begin(u, &ticket);
        locate(&ticket);
        return finish(ticket, out);
    }
    // sample() in steps, each of which prefetches what the next reads: a caller drawing many
    // samples (resampling's candidates) takes every draw through one step before the next, so
    // that the draws' cache misses overlap.
    //  - begin: the row of blocks (a cached marginal), and where the search for the block starts;
    //  - locate: the block and its texel row;
    //  - finish: the texel, from the row's record.
    void begin(Vec2 u, Ticket* ticket) const;
    void locate(Ticket* ticket) const;
    bool finish(const Ticket& ticket, Draw* out) const;
    // Density per unit area at texel (column, row), as sample() computes it.
    float density(int column, int row) const;
    // The inverse of sample(): the u that sample() maps to point p of a texel of non-zero density.
    Vec2 invert(Vec2 p) const;

    int width() const { return width_; }
    int height() const { return height_; }

  private:
    static constexpr int kBlock = 8;
    // A block as a row of blocks lists it: its interval in the row's CDF, and the end of each of
    // its rows' intervals (the last is 1), in one record, as level 1 reads them together.
    struct BlockEntry {
        float start, end;
        std::array<float, kBlock> rowEnd;
    };
    // One row of a block: its texels' interval ends and values, two cache lines that the
    // adjacent-line prefetcher fetches together. Texels past the image's edge (a ragged last
    // block) have empty intervals.
    struct alignas(128) BlockRow {
        std::array<float, kBlock> columnEnd;
        std::array<Rgb, kBlock> value;
    };
    static_assert(sizeof(BlockRow) == 128);

    size_t blockIndex(int bx, int by) const {
        return size_t(by) * size_t(blockColumns_) + size_t(bx);
    }
    const BlockRow& blockRow(int bx, int by, int r) const {
        return blockRows_[blockIndex(bx, by) * kBlock + size_t(r)];
    }
    // The texel's density from the widths of its block's, row's and column's intervals.
    float densityOf(int bx, int by, int r, int c, const BlockRow& row) const;

    int width_ = 0, height_ = 0, blockColumns_ = 0, blockRowCount_ = 0;
    Distribution1D blockRowDistribution_;  // marginal over rows of blocks
    std::vector<BlockEntry> blocks_;       // per row of blocks, its blocks in turn
    std::vector<uint32_t> blockGuide_;     // per row of blocks and slice of [0, 1): a block
    std::vector<BlockRow, HugePageAllocator<BlockRow>> blockRows_;  // per block, kBlock each
    float cells_ = 0;                                               // width × height
};

}  // namespace rr
