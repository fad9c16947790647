#include "io/ply_header.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rr {

namespace fs = std::filesystem;

namespace {

constexpr size_t kMaxHeaderBytes = 1 << 16;
constexpr uint64_t kMaxElementCount = uint64_t(1) << 31;

// Bytes of a PLY scalar type in a binary body; 0 for an unknown type.
size_t scalarBytes(const std::string& type) {
    static const std::map<std::string, size_t> sizes = {
        {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
        {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    const auto it = sizes.find(type);
    return it == sizes.end() ? 0 : it->second;
}

struct Element {
    std::string name;
    uint64_t count = 0;
    uint64_t minimumBytes = 0;  // per item in a binary body (a list at least its count)
    std::vector<std::string> properties;
};

[[noreturn]] void fail(const fs::path& file, const std::string& what) {
    throw std::runtime_error("mesh " + file.string() + ": malformed PLY: " + what);
}

// One header line: printable ASCII only (a trailing \r is dropped).
std::string headerLine(std::istream& in, const fs::path& file, size_t* consumed) {
    std::string line;
    if (!std::getline(in, line)) fail(file, "no end_header");
    *consumed += line.size() + 1;
    if (*consumed > kMaxHeaderBytes) fail(file, "longer than 64 KiB");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    for (char c : line)
        if (c < 32 || c > 126) fail(file, "a non-printable byte before end_header");
    return line;
}

void readProperty(std::istringstream& words, Element* element, const fs::path& file) {
    std::string type, name;
    words >> type;
    if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType >> name;
        if (!scalarBytes(countType) || !scalarBytes(itemType))
            fail(file, "list property \"" + name + "\" of unknown type");
        element->minimumBytes += scalarBytes(countType);
    } else {
        words >> name;
        if (!scalarBytes(type)) fail(file, "property \"" + name + "\" of unknown type");
        element->minimumBytes += scalarBytes(type);
    }
    if (name.empty() || !words.eof()) fail(file, "a property line must name its type and name");
    element->properties.push_back(name);
}

}  // namespace

void checkPlyHeader(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open mesh " + file.string());
    size_t consumed = 0;
    if (headerLine(in, file, &consumed) != "ply") fail(file, "the first line must be \"ply\"");
    bool binary = false, haveFormat = false;
    std::vector<Element> elements;
    for (;;) {
        std::istringstream words(headerLine(in, file, &consumed));
        std::string keyword;
        words >> keyword;
        if (keyword == "end_header") break;
        if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
        if (keyword == "format") {
            std::string format, version;
            words >> format >> version;
            if (format != "ascii" && format != "binary_little_endian" &&
                format != "binary_big_endian")
                fail(file, "unknown format \"" + format + "\"");
            binary = format != "ascii";
            haveFormat = true;
        } else if (keyword == "element") {
            Element e;
            long long count = -1;
            words >> e.name >> count;
            if (e.name.empty() || count < 0 || uint64_t(count) > kMaxElementCount || !words.eof())
                fail(file, "an element line must give a name and a count below 2^31");
            e.count = uint64_t(count);
            elements.push_back(e);
        } else if (keyword == "property") {
            if (elements.empty()) fail(file, "a property before any element");
            readProperty(words, &elements.back(), file);
        } else {
            fail(file, "unknown keyword \"" + keyword + "\"");
        }
    }
    if (!haveFormat) fail(file, "no format line");
    const Element* vertex = nullptr;
    for (const Element& e : elements)
        if (e.name == "vertex") vertex = &e;
    if (!vertex) fail(file, "no vertex element");
    for (const char* axis : {"x", "y", "z"}) {
        bool found = false;
        for (const std::string& p : vertex->properties)
            found = found || p == axis;
        if (!found) fail(file, std::string("the vertex element has no \"") + axis + "\"");
    }
    if (!binary) return;
    // A binary body holds at least every element's fixed part: a shorter file is cut.
    uint64_t needed = 0;
    for (const Element& e : elements)
        needed += e.count * e.minimumBytes;
    const uint64_t size = fs::file_size(file);
    if (size < consumed || size - consumed < needed)
        fail(file, "the binary body is shorter than its elements (" +
                       std::to_string(size - std::min<uint64_t>(size, consumed)) +
                       " bytes, at least " + std::to_string(needed) + " needed)");
}

}  // namespace rr
