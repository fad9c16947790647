// Damaged asset files end to end: a truncated or corrupted mesh or environment map is bad input
// (exit status 2, one message naming the file, nothing written), never a crash or a NaN image.
// The fuzz targets (tests/fuzz/) search for such files; these are the cases named in the issue.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "io/exr_io.h"
#include "support/asset_scene.h"
#include "support/child_process.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

// A tetrahedron, as PLY text and as little-endian binary PLY (x, y, z floats per vertex).
const char* const kVertices[] = {"0 0.6 0", "-0.5 -0.3 0.4", "0.5 -0.3 0.4", "0 -0.3 -0.5"};

std::string asciiPly() {
    std::string text =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
        "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n";
    for (const char* v : kVertices)
        text += std::string(v) + "\n";
    return text + "3 0 1 2\n3 0 2 3\n3 0 3 1\n3 1 3 2\n";
}

std::string binaryPly(float firstX) {
    std::string text =
        "ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty float x\n"
        "property float y\nproperty float z\nelement face 4\n"
        "property list uchar int vertex_indices\nend_header\n";
    const float xyz[4][3] = {
        {firstX, 0.6f, 0}, {-0.5f, -0.3f, 0.4f}, {0.5f, -0.3f, 0.4f}, {0, -0.3f, -0.5f}};
    text.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
    const int faces[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}};
    for (const auto& f : faces) {
        text.push_back(3);
        text.append(reinterpret_cast<const char*>(f), sizeof f);
    }
    return text;
}

// An 8 × 4 EXR with the given channels, every value `value`.
std::string exrBytes(const fs::path& dir, std::initializer_list<const char*> channels,
                     float value) {
    ExrImage image;
    image.width = 8;
    image.height = 4;
    for (const char* c : channels)
        image.channels[c] = std::vector<float>(32, value);
    const fs::path file = dir / "made.exr";
    writeExr(file, image);
    return readText(file);
}

struct DamagedAsset {
    const char* what;
    const char* file;  // written into the scene's directory
    std::function<std::string(const fs::path& dir)> bytes;
};

void PrintTo(const DamagedAsset& d, std::ostream* os) {
    *os << d.what;
}

class DamagedAssets : public ::testing::TestWithParam<DamagedAsset> {};

TEST_P(DamagedAssets, AreBadInputNamingTheFileAndWriteNothing) {
    const fs::path dir = scratchDirectory();
    const DamagedAsset& asset = GetParam();
    const std::string bytes = asset.bytes(dir);
    std::ofstream(dir / asset.file, std::ios::binary) << bytes;
    std::ofstream(dir / "scene.json") << sceneUsingAsset(asset.file);
    const ProcessResult r =
        runProcess(RENDERER_BINARY,
                   {"render", (dir / "scene.json").string(), "--resolution", "4x4", "--spp", "1",
                    "--out", (dir / "out" / "image.exr").string()},
                   dir);
    EXPECT_EQ(r.status, 2) << r.errors;
    EXPECT_EQ(std::count(r.errors.begin(), r.errors.end(), '\n'), 1) << r.errors;
    EXPECT_NE(r.errors.find(asset.file), std::string::npos) << r.errors;
    EXPECT_FALSE(fs::exists(dir / "out")) << "nothing may be written";
}

// Each damaged file's intact version renders: the failures below are the damage's.
TEST(DamagedAssetControls, TheIntactFilesRender) {
    const fs::path dir = scratchDirectory();
    const std::pair<const char*, std::string> intact[] = {
        {"ascii.ply", asciiPly()},
        {"binary.ply", binaryPly(0)},
        {"map.exr", exrBytes(dir, {"R", "G", "B"}, 1)},
    };
    for (const auto& [file, bytes] : intact) {
        std::ofstream(dir / file, std::ios::binary) << bytes;
        std::ofstream(dir / "scene.json") << sceneUsingAsset(file);
        const ProcessResult r =
            runProcess(RENDERER_BINARY,
                       {"render", (dir / "scene.json").string(), "--resolution", "4x4", "--spp",
                        "1", "--no-preview", "--out", (dir / "image.exr").string()},
                       dir);
        EXPECT_EQ(r.status, 0) << file << ": " << r.errors;
    }
}

std::string truncated(const std::string& bytes, size_t keep) {
    return bytes.substr(0, keep);
}

INSTANTIATE_TEST_SUITE_P(
    All, DamagedAssets,
    ::testing::Values(
        DamagedAsset{"ascii_ply_cut_mid_vertex", "cut.ply",
                     [](const fs::path&) {
                         const std::string ply = asciiPly();
                         return truncated(ply, ply.find("\n0.5 -0.3 0.4") + 6);
                     }},
        DamagedAsset{"binary_ply_cut_mid_vertex", "cut_binary.ply",
                     [](const fs::path&) {
                         const std::string ply = binaryPly(0);
                         return truncated(ply, ply.find("end_header\n") + 11 + 18);
                     }},
        DamagedAsset{
            "mesh_with_nan_vertex", "nan.ply",
            [](const fs::path&) { return binaryPly(std::numeric_limits<float>::quiet_NaN()); }},
        DamagedAsset{"exr_with_two_channels", "two_channels.exr",
                     [](const fs::path& dir) {
                         return exrBytes(dir, {"R", "G"}, 1);
                     }},
        DamagedAsset{"exr_cut_mid_pixels", "cut.exr",
                     [](const fs::path& dir) {
                         const std::string exr = exrBytes(dir, {"R", "G", "B"}, 1);
                         return truncated(exr, exr.size() - 40);
                     }},
        DamagedAsset{"exr_with_negative_texels", "negative.exr",
                     [](const fs::path& dir) {
                         return exrBytes(dir, {"R", "G", "B"}, -1);
                     }},
        DamagedAsset{"hdr_with_bad_header", "bad_header.hdr",
                     [](const fs::path&) {
                         return std::string("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 4\n") +
                                std::string(32, '\x80');
                     }}),
    [](const ::testing::TestParamInfo<DamagedAsset>& param) { return param.param.what; });

}  // namespace
}  // namespace rr::test
