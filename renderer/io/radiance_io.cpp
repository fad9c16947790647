#include "io/radiance_io.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rr {

namespace fs = std::filesystem;

namespace {

constexpr int kMaxSide = 1 << 15;
constexpr int64_t kMaxPixels = int64_t(1) << 26;  // 2^28 float values with three channels

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
    throw std::runtime_error("cannot read Radiance HDR " + file.string() + ": " + what);
}

// The file's bytes, read from `pos` on.
class Bytes {
  public:
    Bytes(std::vector<uint8_t> data, const fs::path& file) : data_(std::move(data)), file_(file) {}
    bool atEnd() const { return pos_ >= data_.size(); }
    uint8_t next() {
        if (atEnd()) fail(file_, "the file ends inside the pixels");
        return data_[pos_++];
    }
    std::string line() {
        std::string text;
        while (!atEnd() && data_[pos_] != '\n')
            text.push_back(char(data_[pos_++]));
        if (atEnd()) fail(file_, "the file ends inside the header");
        ++pos_;
        return text;
    }

  private:
    std::vector<uint8_t> data_;
    const fs::path& file_;
    size_t pos_ = 0;
};

Rgb fromRgbe(const uint8_t* rgbe) {
    if (rgbe[3] == 0) return Rgb(0.0f);
    const float scale = static_cast<float>(std::ldexp(1.0f, int(rgbe[3]) - (128 + 8)));
    return Rgb(float(rgbe[0]) * scale, float(rgbe[1]) * scale, float(rgbe[2]) * scale);
}

// One scanline in the run-length encoding: each of the four components in turn, as runs
// (a count above 128, then one value repeated count − 128 times) and literals (a count in
// 1 … 128, then that many values).
void readRunLengthRow(Bytes& in, int width, std::vector<uint8_t>* row, const fs::path& file) {
    for (int component = 0; component < 4; ++component) {
        int x = 0;
        while (x < width) {
            int count = in.next();
            const bool run = count > 128;
            if (run) count -= 128;
            if (count == 0 || count > width - x) fail(file, "a run length out of its scanline");
            if (run) {
                const uint8_t value = in.next();
                for (int k = 0; k < count; ++k)
                    (*row)[size_t(4 * x++ + component)] = value;
            } else {
                for (int k = 0; k < count; ++k)
                    (*row)[size_t(4 * x++ + component)] = in.next();
            }
        }
    }
}

}  // namespace

RgbImage readRadiance(const fs::path& file) {
    std::ifstream stream(file, std::ios::binary);
    if (!stream) fail(file, "cannot open it");
    Bytes in({std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()}, file);
    const std::string magic = in.line();
    if (magic != "#?RADIANCE" && magic != "#?RGBE") fail(file, "not a Radiance file");
    bool rgbe = false;
    for (std::string line = in.line(); !line.empty(); line = in.line())
        rgbe = rgbe || line == "FORMAT=32-bit_rle_rgbe";
    if (!rgbe) fail(file, "no FORMAT=32-bit_rle_rgbe line (only RGBE is read)");
    const std::string resolution = in.line();
    int width = 0, height = 0;
    char rest = 0;
    if (std::sscanf(resolution.c_str(), "-Y %d +X %d%c", &height, &width, &rest) != 2)
        fail(file, "the resolution line must read \"-Y height +X width\"");
    if (width < 1 || height < 1 || width > kMaxSide || height > kMaxSide ||
        int64_t(width) * height > kMaxPixels)
        fail(file, "a resolution of " + std::to_string(width) + " x " + std::to_string(height));

    RgbImage image{width, height, std::vector<Rgb>(size_t(width) * size_t(height))};
    std::vector<uint8_t> row(size_t(4 * width));
    bool flat = width < 8 || width >= kMaxSide;  // run-length rows exist for 8 … 32767 only
    for (int y = 0; y < height; ++y) {
        if (!flat) {
            uint8_t start[4];
            for (uint8_t& b : start)
                b = in.next();
            if (start[0] == 2 && start[1] == 2 && !(start[2] & 0x80)) {
                if ((start[2] << 8 | start[3]) != width) fail(file, "a scanline of another width");
                readRunLengthRow(in, width, &row, file);
            } else {
                // An uncompressed file: these four bytes were its first pixel, and every pixel
                // from here on is flat (as stb_image reads it).
                flat = true;
                std::copy(start, start + 4, row.begin());
                for (size_t i = 4; i < row.size(); ++i)
                    row[i] = in.next();
            }
        } else {
            for (uint8_t& b : row)
                b = in.next();
        }
        for (int x = 0; x < width; ++x)
            image.pixels[size_t(y) * size_t(width) + size_t(x)] = fromRgbe(&row[size_t(4 * x)]);
    }
    return image;
}

}  // namespace rr
