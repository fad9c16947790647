// The Radiance RGBE reader (io/radiance_io.h) against stb_image, which it replaces: the same
// values bit for bit on flat and run-length encoded files (the fuzz seeds, and Galileo's probe
// when it is on the asset search path); and malformed files are errors, not hangs.
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#include "io/radiance_io.h"
#include "loader/asset_resolver.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSeeds = fs::path(FUZZ_CORPUS_DIR) / "hdr";

void expectSameAsStb(const fs::path& file) {
    int width = 0, height = 0, components = 0;
    const std::unique_ptr<float, void (*)(void*)> stb(
        stbi_loadf(file.c_str(), &width, &height, &components, 3), stbi_image_free);
    ASSERT_TRUE(stb) << file;
    const RgbImage ours = readRadiance(file);
    ASSERT_EQ(ours.width, width);
    ASSERT_EQ(ours.height, height);
    for (size_t i = 0; i < ours.pixels.size(); ++i) {
        const Rgb& p = ours.pixels[i];
        const float mine[3] = {p.r, p.g, p.b};
        ASSERT_EQ(std::memcmp(mine, stb.get() + 3 * i, sizeof mine), 0) << file << " pixel " << i;
    }
}

TEST(Radiance, FlatAndRunLengthFilesReadAsStbReadsThem) {
    expectSameAsStb(kSeeds / "flat_4x2.hdr");
    expectSameAsStb(kSeeds / "rle_16x8.hdr");
}

TEST(Radiance, GalileosProbeReadsAsStbReadsIt) {
    const auto probe =
        AssetResolver::standard(TEST_SCENES_DIR).resolve("envmaps/galileo_probe.hdr");
    if (!probe) GTEST_SKIP() << "Galileo's probe is not on the asset search path";
    expectSameAsStb(*probe);
}

void expectError(const std::string& bytes, const std::string& mentions) {
    const fs::path file = scratchDirectory() / "bad.hdr";
    std::ofstream(file, std::ios::binary) << bytes;
    try {
        readRadiance(file);
        FAIL() << "no error for " << mentions;
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(mentions), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
}

TEST(Radiance, MalformedFilesAreErrorsNamingTheFile) {
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
    expectError("P6\n", "not a Radiance file");
    expectError("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 4\n", "FORMAT");
    expectError(header + "+Y 2 +X 4\n", "resolution line");
    expectError(header + "-Y 2 +X 0\n", "resolution of");
    expectError(header + "-Y 2 +X 4\n" + std::string(20, '\x40'), "ends inside the pixels");
    // A run-length scanline of 16 pixels whose first count is 0: stb_image's copy in Debian's
    // libraries loops forever on it.
    expectError(
        header + "-Y 1 +X 16\n" + std::string("\x02\x02\x00\x10\x00", 5) + std::string(64, '\x01'),
        "run length");
    expectError(header + "-Y 1 +X 16\n" + std::string("\x02\x02\x00\x11", 4), "another width");
}

}  // namespace
}  // namespace rr::test
