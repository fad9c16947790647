// The PLY reader (io/ply_reader): the three encodings give the same mesh, polygons are fanned,
// unknown elements and properties are skipped, equal vertices joined, degenerate triangles
// dropped, and each kind of malformed file is an error that says what is wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/ply_reader.h"
#include "support/scratch.h"

namespace rr::test {
namespace {

namespace fs = std::filesystem;

fs::path writeFile(const std::string& name, const std::string& bytes) {
    const fs::path file = scratchDirectory() / name;
    std::ofstream(file, std::ios::binary) << bytes;
    return file;
}

// A square pyramid, its base a quad the reader fans: 5 vertices, 4 triangles + 1 quad. The
// vertices carry normals and a colour, the faces texture coordinates, and a third element
// follows: all read and skipped.
const float kVertices[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 1}};
const std::vector<std::vector<int>> kFaces = {
    {0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};

std::string header(const std::string& format) {
    return "ply\nformat " + format +
           " 1.0\ncomment written by test_ply_reader\nelement vertex 5\nproperty float x\n"
           "property float y\nproperty float z\nproperty float nx\nproperty float ny\n"
           "property float nz\nproperty uchar red\nelement face 5\n"
           "property list uchar int vertex_indices\nproperty list uchar float texcoord\n"
           "element material 1\nproperty float shininess\nend_header\n";
}

std::string asciiPly() {
    std::ostringstream s;
    s << header("ascii") << std::fixed;
    for (auto& v : kVertices)
        s << v[0] << " " << v[1] << " " << v[2] << " 0 0 1 255\n";
    for (const auto& f : kFaces) {
        s << f.size();
        for (int i : f)
            s << " " << i;
        s << " 2 0.25 0.5\n";
    }
    s << "0.5\n";
    return s.str();
}

template <typename T>
void append(std::string* s, T value, bool bigEndian) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (bigEndian == (std::endian::native == std::endian::little))
        std::reverse(raw, raw + sizeof(T));
    s->append(raw, sizeof(T));
}

std::string binaryPly(bool bigEndian) {
    std::string s = header(bigEndian ? "binary_big_endian" : "binary_little_endian");
    for (auto& v : kVertices) {
        for (float c : v)
            append(&s, c, bigEndian);
        for (float n : {0.0f, 0.0f, 1.0f})
            append(&s, n, bigEndian);
        append(&s, uint8_t(255), bigEndian);
    }
    for (const auto& f : kFaces) {
        append(&s, uint8_t(f.size()), bigEndian);
        for (int i : f)
            append(&s, int32_t(i), bigEndian);
        append(&s, uint8_t(2), bigEndian);
        append(&s, 0.25f, bigEndian);
        append(&s, 0.5f, bigEndian);
    }
    append(&s, 0.5f, bigEndian);
    return s;
}

TEST(PlyReader, AsciiAndBothBinaryOrdersGiveTheSameFannedMesh) {
    const MeshData ascii = readPly(writeFile("a.ply", asciiPly()));
    ASSERT_EQ(ascii.positions.size(), 5u);
    for (int v = 0; v < 5; ++v)
        EXPECT_EQ(ascii.positions[size_t(v)],
                  Vec3(kVertices[v][0], kVertices[v][1], kVertices[v][2]));
    const std::vector<uint32_t> fanned = {0, 3, 2, 0, 2, 1, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4};
    EXPECT_EQ(ascii.indices, fanned);
    EXPECT_TRUE(ascii.normals.empty());  // the file's normals are not the mesh's
    for (bool bigEndian : {false, true}) {
        const MeshData binary = readPly(writeFile("b.ply", binaryPly(bigEndian)));
        EXPECT_EQ(binary.positions, ascii.positions) << "big endian " << bigEndian;
        EXPECT_EQ(binary.indices, ascii.indices) << "big endian " << bigEndian;
    }
}

// An ASCII float32 rounds once, to the nearest float (through double it would round to 1).
TEST(PlyReader, AsciiFloatsRoundToTheNearestFloat) {
    const std::string s =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "1.0000000596046447753906251 0 0\n0 1 0\n0 0 1\n3 0 1 2\n";
    const MeshData mesh = readPly(writeFile("r.ply", s));
    EXPECT_EQ(mesh.positions[0].x, std::nextafter(1.0f, 2.0f));
}

TEST(PlyReader, JoinsEqualVerticesAndDropsDegenerateTriangles) {
    const std::string s =
        "ply\r\nformat ascii 1.0\r\nelement vertex 5\r\nproperty double x\r\nproperty double y\r\n"
        "property double z\r\nelement face 3\r\nproperty list uchar uint "
        "vertex_index\r\nend_header\r\n"
        "0 0 0\r\n1 0 0\r\n0 1 0\r\n1 0 0\r\n0 0 0\r\n"
        "3 0 1 2\r\n3 2 3 4\r\n3 0 1 4\r\n";
    const MeshData mesh = readPly(writeFile("d.ply", s));
    EXPECT_EQ(mesh.positions.size(), 3u);                   // vertices 3 and 4 repeat 1 and 0
    const std::vector<uint32_t> kept = {0, 1, 2, 2, 1, 0};  // the third face has corner 0 twice
    EXPECT_EQ(mesh.indices, kept);
}

// Each malformed file throws, naming the file and the defect.
struct Malformed {
    const char* name;
    std::string bytes;
    const char* message;
};

std::vector<Malformed> malformedFiles() {
    const std::string ascii = asciiPly();
    const std::string binary = binaryPly(false);
    const std::string bigEndian = binaryPly(true);
    auto replace = [](std::string s, const std::string& from, const std::string& to) {
        return s.replace(s.find(from), from.size(), to);
    };
    return {
        {"not_ply", "plx\n" + ascii.substr(4), "the first line must be"},
        {"unknown_type", replace(ascii, "property float y", "property float16 y"), "unknown type"},
        {"no_z", replace(ascii, "property float z", "property float w"), "no \"z\""},
        {"ascii_cut_mid_vertex", ascii.substr(0, ascii.find("1.000000 1.000000") + 9),
         "ends before"},
        {"binary_cut", binary.substr(0, binary.size() - 3), "ends before"},
        {"trailing_bytes", ascii + "7\n", "after the last element"},
        {"binary_trailing_bytes", binary + "x", "after the last element"},
        {"index_past_vertices", replace(ascii, "3 0 1 4", "3 0 1 5"), "missing vertex"},
        {"negative_index", replace(ascii, "3 0 1 4", "3 0 -1 4"), "missing vertex"},
        {"fractional_index", replace(ascii, "3 0 1 4", "3 0 1.5 4"), "not an integer"},
        {"count_beyond_type", replace(ascii, " 255\n", " 256\n"), "does not fit"},
        {"negative_list_count",
         replace(replace(ascii, "list uchar int", "list char int"), "3 0 1 4", "-1 0 1 4"),
         "past the end"},
        {"float_out_of_range", replace(ascii, "0.500000 0.500000 1.000000", "0.5 1e39 1"),
         "out of its type's range"},
        {"unknown_keyword", replace(ascii, "comment written", "commentary written"),
         "unknown keyword"},
        {"unknown_format", replace(ascii, "format ascii", "format text"), "unknown format"},
        {"format_without_version", replace(ascii, "format ascii 1.0", "format ascii"),
         "a format line"},
        {"no_format", replace(ascii, "format ascii 1.0\n", ""), "no format line"},
        {"no_end_header", ascii.substr(0, ascii.find("end_header")), "no end_header"},
        {"long_header", "ply\nformat ascii 1.0\n" + std::string(70000, ' ') + "\n",
         "longer than 64 KiB"},
        {"property_before_element", replace(ascii, "element vertex 5\n", ""),
         "a property before any element"},
        {"two_vertex_elements", replace(ascii, "element material 1", "element vertex 1"),
         "two vertex elements"},
        {"list_coordinate", replace(ascii, "property float x", "property list uchar float x"),
         "must not be lists"},
        {"big_endian_cut", bigEndian.substr(0, bigEndian.size() - 3), "ends before"},
        {"not_a_number", replace(ascii, "0.500000 0.500000 1.000000", "0.5 nope 1"),
         "not a number"},
        {"face_of_two", replace(ascii, "3 0 1 4", "2 0 1 4"), "fewer than 3"},
        {"no_index_list", replace(ascii, "vertex_indices", "corners"), "no vertex_indices"},
        {"float_indices", replace(ascii, "uchar int vertex_indices", "uchar float vertex_indices"),
         "must be a list of integers"},
        {"huge_list",
         replace(binary, std::string("\x04\x00\x00\x00\x00", 5),
                 std::string("\xff\x00\x00\x00\x00", 5)),
         "past the end"},
        {"face_before_vertex",
         "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nelement "
         "vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
         "before the vertex element"},
        {"count_too_large", replace(ascii, "element vertex 5", "element vertex 4294967296"),
         "below 2^31"},
        {"element_without_properties",
         replace(ascii, "element material 1\nproperty float shininess\n", "element material 1\n"),
         "has no properties"},
        {"binary_in_header", replace(ascii, "element face", std::string("element \x01 face")),
         "non-printable"},
    };
}

TEST(PlyReader, MalformedFilesAreErrorsNamingTheDefect) {
    for (const Malformed& m : malformedFiles()) {
        const fs::path file = writeFile(std::string(m.name) + ".ply", m.bytes);
        try {
            (void)readPly(file);
            ADD_FAILURE() << m.name << ": no error";
        } catch (const std::runtime_error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(file.string()), std::string::npos) << m.name << ": " << what;
            EXPECT_NE(what.find(m.message), std::string::npos) << m.name << ": " << what;
        }
    }
}

}  // namespace
}  // namespace rr::test
