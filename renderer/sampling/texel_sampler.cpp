#include "sampling/texel_sampler.h"

#include <algorithm>

namespace rr {

namespace {

// Ends of the intervals of n weights, normalised (uniform when all are zero), then `ends` padded
// with 1: running sums in double, each rounded once, so the ends are monotone and a zero weight's
// interval is empty.
void intervalEnds(std::span<const double> weights, std::span<float> ends) {
    double total = 0;
    for (double w : weights)
        total += w;
    double running = 0;
    for (size_t i = 0; i < weights.size(); ++i) {
        running += total > 0 ? weights[i] / total : 1.0 / double(weights.size());
        ends[i] = static_cast<float>(running);
    }
    for (size_t i = weights.size() - 1; i < ends.size(); ++i)
        ends[i] = 1.0f;
}

template <size_t N>
float intervalStart(const std::array<float, N>& ends, int i) {
    return i > 0 ? ends[size_t(i) - 1] : 0.0f;
}

// The interval of `ends` that holds u ∈ [0, 1) (the number of ends at or below u: empty intervals
// are passed over), and u remapped to [0, 1) within it.
template <size_t N>
int findInterval(const std::array<float, N>& ends, float u, float* remapped) {
    int i = 0;
    for (size_t k = 0; k + 1 < N; ++k)
        i += ends[k] <= u ? 1 : 0;
    const float low = intervalStart(ends, i);
    *remapped = std::min((u - low) / (ends[size_t(i)] - low), kOneMinusEpsilon);
    return i;
}

}  // namespace

TexelSampler::TexelSampler(std::span<const float> weights, std::span<const Rgb> values, int width,
                           int height)
    : width_(width),
      height_(height),
      blockColumns_((width + kBlock - 1) / kBlock),
      blockRowCount_((height + kBlock - 1) / kBlock),
      cells_(float(width) * float(height)) {
    const size_t columns = size_t(blockColumns_), blocks = columns * size_t(blockRowCount_);
    blocks_.resize(blocks);
    blockRows_.resize(blocks * kBlock);
    std::vector<double> blockWeights(blocks);
    // All zero: uniform over the texels (not over the blocks, which a ragged edge makes
    // unequal).
    const bool allZero =
        std::none_of(weights.begin(), weights.end(), [](float w) { return w > 0; });
    for (int by = 0; by < blockRowCount_; ++by)
        for (int bx = 0; bx < blockColumns_; ++bx) {
            // The block's texels within the image (a last block may be ragged).
            const int texelColumns = std::min(kBlock, width - bx * kBlock);
            const int texelRows = std::min(kBlock, height - by * kBlock);
            std::array<double, kBlock> rowWeights{};
            for (int r = 0; r < kBlock; ++r) {
                BlockRow& blockRow = blockRows_[blockIndex(bx, by) * kBlock + size_t(r)];
                std::array<double, kBlock> w{};
                for (int c = 0; r < texelRows && c < texelColumns; ++c) {
                    const size_t i =
                        size_t(by * kBlock + r) * size_t(width) + size_t(bx * kBlock + c);
                    w[size_t(c)] = allZero ? 1.0 : weights[i];
                    blockRow.value[size_t(c)] = values[i];
                    rowWeights[size_t(r)] += w[size_t(c)];
                }
                intervalEnds(std::span(w).first(size_t(texelColumns)), blockRow.columnEnd);
            }
            intervalEnds(std::span(rowWeights).first(size_t(texelRows)),
                         blocks_[blockIndex(bx, by)].rowEnd);
            for (double x : rowWeights)
                blockWeights[blockIndex(bx, by)] += x;
        }
    std::vector<float> blockRowWeights(static_cast<size_t>(blockRowCount_));
    blockGuide_.assign(blocks, 0);
    std::vector<float> ends(columns);
    for (int by = 0; by < blockRowCount_; ++by) {
        const std::span<const double> row(&blockWeights[blockIndex(0, by)], columns);
        double sum = 0;
        for (double x : row)
            sum += x;
        blockRowWeights[size_t(by)] = static_cast<float>(sum);
        intervalEnds(row, ends);
        for (size_t bx = 0; bx < columns; ++bx) {
            BlockEntry& block = blocks_[blockIndex(int(bx), by)];
            block.start = bx > 0 ? ends[bx - 1] : 0.0f;
            block.end = ends[bx];
        }
        // Slice k of [0, 1): the last block whose interval starts at or below k/columns
        // (compared in double, as locate() computes the slice).
        size_t g = 0;
        for (size_t k = 0; k < columns; ++k) {
            while (g + 1 < columns && double(ends[g]) <= double(k) / double(columns))
                ++g;
            blockGuide_[blockIndex(int(k), by)] = uint32_t(g);
        }
    }
    blockRowDistribution_ = Distribution1D(blockRowWeights);
}

float TexelSampler::densityOf(int bx, int by, int r, int c, const BlockRow& row) const {
    const BlockEntry& block = blocks_[blockIndex(bx, by)];
    const float rowWidth = block.rowEnd[size_t(r)] - intervalStart(block.rowEnd, r);
    const float columnWidth = row.columnEnd[size_t(c)] - intervalStart(row.columnEnd, c);
    return blockRowDistribution_.pmf(by) * (block.end - block.start) *
           (rowWidth * columnWidth * cells_);
}

float TexelSampler::density(int column, int row) const {
    const int bx = column / kBlock, by = row / kBlock, r = row % kBlock;
    return densityOf(bx, by, r, column % kBlock, blockRow(bx, by, r));
}

void TexelSampler::begin(Vec2 u, Ticket* t) const {
    t->blockRow = blockRowDistribution_.sample(u.y, nullptr, &t->uy);
    t->ux = u.x;
    // The search for the block starts from the guide's (the slice's start ⌊u.x·n⌋/n is at most
    // u.x: u.x·n is exact in double).
    const size_t columns = size_t(blockColumns_);
    const size_t slice =
        std::min(size_t(std::max(double(u.x), 0.0) * double(columns)), columns - 1);
    t->blockColumn = int(blockGuide_[blockIndex(int(slice), t->blockRow)]);
    __builtin_prefetch(&blocks_[blockIndex(t->blockColumn, t->blockRow)]);
}

void TexelSampler::locate(Ticket* t) const {
    // The block: the last one whose interval starts at or below u.x.
    const BlockEntry* row = &blocks_[blockIndex(0, t->blockRow)];
    size_t bx = size_t(t->blockColumn);
    while (bx + 1 < size_t(blockColumns_) && row[bx].end <= t->ux)
        ++bx;
    const BlockEntry& block = row[bx];
    t->blockColumn = int(bx);
    t->ux = std::min((t->ux - block.start) / (block.end - block.start), kOneMinusEpsilon);
    t->row = findInterval(block.rowEnd, t->uy, &t->v);
    __builtin_prefetch(&blockRow(t->blockColumn, t->blockRow, t->row));
}

bool TexelSampler::finish(const Ticket& t, Draw* out) const {
    const int bx = t.blockColumn, by = t.blockRow, r = t.row;
    const BlockRow& row = blockRow(bx, by, r);
    float s;
    const int c = findInterval(row.columnEnd, t.ux, &s);
    const int column = bx * kBlock + c, imageRow = by * kBlock + r;
    out->density = densityOf(bx, by, r, c, row);
    // Past the image's edge or of zero width: an empty interval, reached only by rounding.
    if (column >= width_ || imageRow >= height_ || !(out->density > 0)) return false;
    out->point =
        Vec2((float(column) + s) / float(width_), (float(imageRow) + t.v) / float(height_));
    out->column = column;
    out->row = imageRow;
    out->value = row.value[size_t(c)];
    return true;
}

Vec2 TexelSampler::invert(Vec2 p) const {
    const float x = std::clamp(p.x, 0.0f, 1.0f) * float(width_);
    const float y = std::clamp(p.y, 0.0f, 1.0f) * float(height_);
    const int column = std::clamp(static_cast<int>(x), 0, width_ - 1);
    const int row = std::clamp(static_cast<int>(y), 0, height_ - 1);
    const int bx = column / kBlock, by = row / kBlock, r = row % kBlock, c = column % kBlock;
    // Within the texel, then within the block's row and column intervals, then the block's.
    const float fx = std::clamp(x - float(column), 0.0f, 1.0f);
    const float fy = std::clamp(y - float(row), 0.0f, 1.0f);
    const auto& columnEnd = blockRow(bx, by, r).columnEnd;
    const BlockEntry& block = blocks_[blockIndex(bx, by)];
    const float columnStart = intervalStart(columnEnd, c);
    const float rowStart = intervalStart(block.rowEnd, r);
    const float ux =
        std::min(columnStart + fx * (columnEnd[size_t(c)] - columnStart), kOneMinusEpsilon);
    const float uy =
        std::min(rowStart + fy * (block.rowEnd[size_t(r)] - rowStart), kOneMinusEpsilon);
    return {std::min(block.start + ux * (block.end - block.start), kOneMinusEpsilon),
            blockRowDistribution_.invert(by, uy)};
}

}  // namespace rr
