// EXR output: channels and metadata survive a round trip; writes are atomic.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "io/exr_io.h"
#include "render/render_output.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

TEST(Exr, FilmChannelsAndMetadataRoundTrip) {
    Film film(5, 3);
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 5; ++x) {
            film.add(x, y, Rgb(float(x), float(y), 0.5f));
            film.add(x, y, Rgb(float(x) + 1, float(y), 1.5f));
        }
    ExrImage image = filmToExr(film);
    image.attributes["renderer.integrator"] = std::string("path_mis");
    image.attributes["renderer.spp"] = 2;
    image.attributes["renderer.renderTime"] = 1.25;

    const fs::path file = scratchDirectory() / "image.exr";
    writeExr(file, image);
    const ExrImage back = readExr(file);
    EXPECT_EQ(back.width, 5);
    EXPECT_EQ(back.height, 3);
    for (const char* name : {"R", "G", "B", "variance.R", "variance.G", "variance.B", "samples"})
        ASSERT_EQ(back.channels.at(name), image.channels.at(name)) << name;
    // Pixel (2, 1): samples (2,1,.5) and (3,1,1.5): mean (2.5, 1, 1), variance of the mean
    // = sample variance / n = 0.5 / 2 for R and B, 0 for G.
    const size_t i = 1 * 5 + 2;
    EXPECT_FLOAT_EQ(back.channels.at("R")[i], 2.5f);
    EXPECT_FLOAT_EQ(back.channels.at("variance.R")[i], 0.25f);
    EXPECT_FLOAT_EQ(back.channels.at("variance.G")[i], 0.0f);
    EXPECT_FLOAT_EQ(back.channels.at("variance.B")[i], 0.25f);
    EXPECT_FLOAT_EQ(back.channels.at("samples")[i], 2.0f);
    EXPECT_EQ(std::get<std::string>(back.attributes.at("renderer.integrator")), "path_mis");
    EXPECT_EQ(std::get<int>(back.attributes.at("renderer.spp")), 2);
    EXPECT_DOUBLE_EQ(std::get<double>(back.attributes.at("renderer.renderTime")), 1.25);
}

TEST(Exr, WriteLeavesNoTemporaryFiles) {
    const fs::path dir = scratchDirectory();
    ExrImage image = filmToExr(Film(4, 4));
    writeExr(dir / "a.exr", image);
    writeExr(dir / "a.exr", image);  // replacing an existing file
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        ++files;
        EXPECT_EQ(entry.path().filename(), "a.exr");
    }
    EXPECT_EQ(files, 1);
}

TEST(Exr, FailedWriteThrowsAndLeavesNothing) {
    const fs::path dir = scratchDirectory();
    ExrImage image = filmToExr(Film(4, 4));
    image.channels["broken"] = std::vector<float>(3);  // wrong size: the writer refuses
    EXPECT_THROW(writeExr(dir / "b.exr", image), std::exception);
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Exr, ReadingAMissingFileNamesIt) {
    try {
        readExr("/nonexistent/file.exr");
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/file.exr"), std::string::npos);
    }
}

// A header attribute whose declared size exceeds the file is refused by its name before
// OpenEXR would allocate that size (the fuzz finding regressions/exr/openexr_2gb_string_...).
TEST(Exr, AnAttributeLargerThanTheFileIsRefusedBeforeReading) {
    const fs::path file = scratchDirectory() / "huge_attribute.exr";
    writeExr(file, filmToExr(Film(2, 2)));
    std::string bytes;
    {
        std::ifstream in(file, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    // The first attribute's size follows its name and type, 8 bytes into the file.
    const size_t name = bytes.find('\0', 8), type = bytes.find('\0', name + 1);
    bytes.replace(type + 1, 4, std::string("\x00\x00\x00\x7a", 4));  // 2 GiB
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
    try {
        readExr(file);
        FAIL();
    } catch (const std::runtime_error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("malformed header: attribute \"" + bytes.substr(8, name - 8) + "\""),
                  std::string::npos)
            << what;
    }
}

// The same in a multi-part file's second header (part 0 is well formed).
TEST(Exr, AnAttributeLargerThanTheFileInALaterPartIsRefused) {
    const fs::path file = scratchDirectory() / "multipart.exr";
    using namespace std::string_literals;
    std::ofstream(file, std::ios::binary)
        << "\x76\x2f\x31\x01\x02\x10\x00\x00"s  // magic; version 2, multi-part
        << "name\0string\0\x01\x00\x00\x00"s
        << "a"
        << "\0"s                              // part 0: one attribute, end
        << "big\0string\0\x00\x00\x00\x7a"s;  // part 1: 2 GiB declared
    try {
        readExr(file);
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("malformed header: attribute \"big\""),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace rr::test
