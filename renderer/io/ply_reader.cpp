#include "io/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace rr {

namespace fs = std::filesystem;

namespace {

constexpr size_t kMaxHeaderBytes = 1 << 16;
constexpr uint64_t kMaxElementCount = uint64_t(1) << 31;

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<ScalarType> scalarType(const std::string& name) {
    static const std::map<std::string, ScalarType> types = {
        {"char", ScalarType::Int8},      {"int8", ScalarType::Int8},
        {"uchar", ScalarType::UInt8},    {"uint8", ScalarType::UInt8},
        {"short", ScalarType::Int16},    {"int16", ScalarType::Int16},
        {"ushort", ScalarType::UInt16},  {"uint16", ScalarType::UInt16},
        {"int", ScalarType::Int32},      {"int32", ScalarType::Int32},
        {"uint", ScalarType::UInt32},    {"uint32", ScalarType::UInt32},
        {"float", ScalarType::Float32},  {"float32", ScalarType::Float32},
        {"double", ScalarType::Float64}, {"float64", ScalarType::Float64}};
    const auto it = types.find(name);
    if (it == types.end()) return std::nullopt;
    return it->second;
}

size_t scalarBytes(ScalarType type) {
    switch (type) {
        case ScalarType::Int8:
        case ScalarType::UInt8:
            return 1;
        case ScalarType::Int16:
        case ScalarType::UInt16:
            return 2;
        case ScalarType::Int32:
        case ScalarType::UInt32:
        case ScalarType::Float32:
            return 4;
        case ScalarType::Float64:
            return 8;
    }
    return 0;
}

bool isInteger(ScalarType type) {
    return type != ScalarType::Float32 && type != ScalarType::Float64;
}

struct Property {
    std::string name;
    ScalarType type = ScalarType::Float32;  // the items' type, for a list
    std::optional<ScalarType> listCount;    // set for a list property
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t bodyOffset = 0;
};

class PlyError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& what) {
    throw PlyError(what);
}

// ---- header -------------------------------------------------------------------------------

// The next header line of `bytes` from `*offset`: printable ASCII only (a trailing \r dropped).
std::string headerLine(const std::vector<char>& bytes, size_t* offset) {
    const size_t end = std::min(bytes.size(), kMaxHeaderBytes);
    size_t newline = *offset;
    while (newline < end && bytes[newline] != '\n')
        ++newline;
    if (newline == end)
        fail(end == kMaxHeaderBytes ? "a header longer than 64 KiB" : "no end_header");
    std::string line(bytes.begin() + std::ptrdiff_t(*offset),
                     bytes.begin() + std::ptrdiff_t(newline));
    *offset = newline + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // Comments may hold any text (UTF-8, say); the lines the reader parses are ASCII words.
    const bool comment = line.starts_with("comment") || line.starts_with("obj_info");
    for (char c : line)
        if (!comment && (c < 32 || c > 126) && c != '\t')
            fail("a non-printable byte before end_header");
    return line;
}

// True when nothing but spaces is left on a header line.
bool atEnd(std::istringstream& words) {
    words >> std::ws;
    return words.eof();
}

Property readProperty(std::istringstream& words) {
    std::string type;
    Property property;
    words >> type;
    if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType >> property.name;
        property.listCount = scalarType(countType);
        const auto item = scalarType(itemType);
        if (!property.listCount || !item || !isInteger(*property.listCount))
            fail("list property \"" + property.name + "\" of unknown type");
        property.type = *item;
    } else {
        words >> property.name;
        const auto scalar = scalarType(type);
        if (!scalar) fail("property \"" + property.name + "\" of unknown type");
        property.type = *scalar;
    }
    if (property.name.empty() || !atEnd(words)) fail("a property line must name its type and name");
    return property;
}

Header readHeader(const std::vector<char>& bytes) {
    Header header;
    size_t offset = 0;
    if (headerLine(bytes, &offset) != "ply") fail("the first line must be \"ply\"");
    bool haveFormat = false;
    for (;;) {
        std::istringstream words(headerLine(bytes, &offset));
        std::string keyword;
        words >> keyword;
        if (keyword == "end_header") break;
        if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
        if (keyword == "format") {
            std::string format, version;
            words >> format >> version;
            if (version.empty() || !atEnd(words))
                fail("a format line must give the format and a version");
            if (format == "ascii")
                header.format = Format::Ascii;
            else if (format == "binary_little_endian")
                header.format = Format::BinaryLittleEndian;
            else if (format == "binary_big_endian")
                header.format = Format::BinaryBigEndian;
            else
                fail("unknown format \"" + format + "\"");
            haveFormat = true;
        } else if (keyword == "element") {
            Element e;
            long long count = -1;
            words >> e.name >> count;
            if (e.name.empty() || count < 0 || uint64_t(count) >= kMaxElementCount || !atEnd(words))
                fail("an element line must give a name and a count below 2^31");
            e.count = uint64_t(count);
            header.elements.push_back(e);
        } else if (keyword == "property") {
            if (header.elements.empty()) fail("a property before any element");
            header.elements.back().properties.push_back(readProperty(words));
        } else {
            fail("unknown keyword \"" + keyword + "\"");
        }
    }
    if (!haveFormat) fail("no format line");
    header.bodyOffset = offset;
    return header;
}

// ---- body ---------------------------------------------------------------------------------

// Reads the body's numbers in order, as doubles (exact for every PLY integer type).
class BodyReader {
  public:
    BodyReader(const std::vector<char>& bytes, size_t offset, Format format)
        : bytes_(bytes), offset_(offset), format_(format) {}

    double next(ScalarType type) {
        return format_ == Format::Ascii ? nextText(type) : nextBinary(type);
    }

    // Bytes left; an upper bound on the numbers left, each at least one byte.
    size_t remaining() const { return bytes_.size() - offset_; }

    void expectEnd() {
        if (format_ == Format::Ascii) skipSpace();
        if (offset_ != bytes_.size()) fail("bytes after the last element");
    }

  private:
    void skipSpace() {
        while (offset_ < bytes_.size() && (bytes_[offset_] == ' ' || bytes_[offset_] == '\t' ||
                                           bytes_[offset_] == '\n' || bytes_[offset_] == '\r'))
            ++offset_;
    }

    // A token for a message: at most 32 characters, bytes outside printable ASCII as '?'.
    static std::string quoted(const char* first, const char* last) {
        std::string s(first, std::min(last, first + 32));
        for (char& c : s)
            if (c < 32 || c > 126) c = '?';
        return "\"" + s + (last - first > 32 ? "...\"" : "\"");
    }

    double nextText(ScalarType type) {
        skipSpace();
        const char* first = bytes_.data() + offset_;
        const char* last = first;
        const char* end = bytes_.data() + bytes_.size();
        while (last < end && *last != ' ' && *last != '\t' && *last != '\n' && *last != '\r')
            ++last;
        if (first == last) fail("the body ends before its elements do");
        offset_ += size_t(last - first);
        double value = 0;
        if (isInteger(type)) {
            int64_t integer = 0;
            const auto [ptr, ec] = std::from_chars(first, last, integer);
            if (ec != std::errc() || ptr != last) fail(quoted(first, last) + " is not an integer");
            value = double(integer);
            if (!fitsType(type, value)) fail(quoted(first, last) + " does not fit its type");
        } else {
            const auto [ptr, ec] = type == ScalarType::Float32
                                       ? parseFloat(first, last, &value)
                                       : std::from_chars(first, last, value);
            if (ec == std::errc::result_out_of_range)
                fail(quoted(first, last) + " is out of its type's range");
            if (ec != std::errc() || ptr != last) fail(quoted(first, last) + " is not a number");
        }
        return value;
    }

    // A float32 value parses to the nearest float, as a binary file stores it.
    static std::from_chars_result parseFloat(const char* first, const char* last, double* value) {
        float f = 0;
        const auto result = std::from_chars(first, last, f);
        *value = f;
        return result;
    }

    // Whether the integer `value` is within the range of the integer `type`.
    static bool fitsType(ScalarType type, double value) {
        auto within = [value](auto lo, auto hi) {
            return value >= double(lo) && value <= double(hi);
        };
        switch (type) {
            case ScalarType::Int8:
                return within(INT8_MIN, INT8_MAX);
            case ScalarType::UInt8:
                return within(0, UINT8_MAX);
            case ScalarType::Int16:
                return within(INT16_MIN, INT16_MAX);
            case ScalarType::UInt16:
                return within(0, UINT16_MAX);
            case ScalarType::Int32:
                return within(INT32_MIN, INT32_MAX);
            case ScalarType::UInt32:
                return within(0, UINT32_MAX);
            default:
                return true;
        }
    }

    double nextBinary(ScalarType type) {
        const size_t n = scalarBytes(type);
        if (remaining() < n) fail("the body ends before its elements do");
        uint8_t raw[8];
        std::memcpy(raw, bytes_.data() + offset_, n);
        offset_ += n;
        const bool swap =
            (format_ == Format::BinaryBigEndian) == (std::endian::native == std::endian::little);
        if (swap) std::reverse(raw, raw + n);
        return decode(type, raw);
    }

    static double decode(ScalarType type, const uint8_t* raw) {
        auto as = [raw]<typename T>(T) {
            T v;
            std::memcpy(&v, raw, sizeof(T));
            return double(v);
        };
        switch (type) {
            case ScalarType::Int8:
                return as(int8_t());
            case ScalarType::UInt8:
                return as(uint8_t());
            case ScalarType::Int16:
                return as(int16_t());
            case ScalarType::UInt16:
                return as(uint16_t());
            case ScalarType::Int32:
                return as(int32_t());
            case ScalarType::UInt32:
                return as(uint32_t());
            case ScalarType::Float32:
                return as(float());
            case ScalarType::Float64:
                return as(double());
        }
        return 0;
    }

    const std::vector<char>& bytes_;
    size_t offset_;
    Format format_;
};

// Where the vertex element's x, y and z are, by index into its properties.
struct VertexLayout {
    size_t position[3] = {0, 0, 0};
};

VertexLayout vertexLayout(const Element& vertex) {
    VertexLayout layout;
    static const char* const names[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
        size_t p = 0;
        while (p < vertex.properties.size() && vertex.properties[p].name != names[k])
            ++p;
        if (p == vertex.properties.size())
            fail(std::string("the vertex element has no \"") + names[k] + "\"");
        if (vertex.properties[p].listCount) fail("vertex coordinates must not be lists");
        layout.position[k] = p;
    }
    return layout;
}

int faceIndexProperty(const Element& face) {
    for (size_t p = 0; p < face.properties.size(); ++p) {
        const Property& property = face.properties[p];
        if (property.name != "vertex_indices" && property.name != "vertex_index") continue;
        if (!property.listCount || !isInteger(property.type))
            fail("the face element's \"" + property.name + "\" must be a list of integers");
        return int(p);
    }
    fail("the face element has no vertex_indices list");
}

// Reads one item of `element`: its scalars into `values` (by property), the indices of the
// list property `listProperty` (if any) into `list`; other lists are read and dropped.
void readItem(BodyReader& body, const Element& element, int listProperty,
              std::vector<double>* values, std::vector<double>* list) {
    values->assign(element.properties.size(), 0.0);
    list->clear();
    for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.listCount) {
            (*values)[p] = body.next(property.type);
            continue;
        }
        const double count = body.next(*property.listCount);
        if (count < 0 || count > double(body.remaining()))
            fail("a list count past the end of the file");
        for (uint64_t i = 0, n = uint64_t(count); i < n; ++i) {
            const double v = body.next(property.type);
            if (int(p) == listProperty) list->push_back(v);
        }
    }
}

// Joins vertices with identical position bits and drops triangles with two equal corners
// (equal by value, so +0 and -0 are one corner there).
class MeshBuilder {
  public:
    void addVertex(const Vec3& position) {
        Key key{};
        std::memcpy(key.bits, &position, sizeof(Vec3));
        const auto [it, inserted] = joined_.try_emplace(key, uint32_t(mesh_.positions.size()));
        if (inserted) mesh_.positions.push_back(position);
        fileToJoined_.push_back(it->second);
    }

    void addPolygon(const std::vector<double>& corners, uint64_t face) {
        if (corners.size() < 3) fail("face " + std::to_string(face) + " has fewer than 3 vertices");
        for (double c : corners)
            if (!(c >= 0 && c < double(fileToJoined_.size())))
                fail("face " + std::to_string(face) + " indexes a missing vertex");
        for (size_t i = 1; i + 1 < corners.size(); ++i)  // a fan from the first corner
            addTriangle(fileToJoined_[size_t(corners[0])], fileToJoined_[size_t(corners[i])],
                        fileToJoined_[size_t(corners[i + 1])]);
    }

    MeshData take() { return std::move(mesh_); }

  private:
    struct Key {
        uint32_t bits[3];
        static_assert(sizeof(Vec3) == sizeof(bits));
        bool operator==(const Key& o) const { return std::memcmp(bits, o.bits, sizeof(bits)) == 0; }
    };
    struct KeyHash {
        size_t operator()(const Key& k) const {
            uint64_t h = 1469598103934665603ull;  // FNV-1a over the words
            for (uint32_t w : k.bits)
                h = (h ^ w) * 1099511628211ull;
            return size_t(h);
        }
    };

    void addTriangle(uint32_t a, uint32_t b, uint32_t c) {
        const auto& p = mesh_.positions;
        if (p[a] == p[b] || p[b] == p[c] || p[c] == p[a]) return;
        mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
    }

    MeshData mesh_;
    std::unordered_map<Key, uint32_t, KeyHash> joined_;
    std::vector<uint32_t> fileToJoined_;
};

MeshData readBody(const std::vector<char>& bytes, const Header& header) {
    const Element* vertexElement = nullptr;
    for (const Element& e : header.elements) {
        if (e.count > 0 && e.properties.empty())
            fail("element \"" + e.name + "\" has no properties");
        if (e.name != "vertex") continue;
        if (vertexElement) fail("two vertex elements");
        vertexElement = &e;
    }
    if (!vertexElement) fail("no vertex element");
    const VertexLayout layout = vertexLayout(*vertexElement);
    MeshBuilder builder;
    BodyReader body(bytes, header.bodyOffset, header.format);
    std::vector<double> values, list;
    bool verticesRead = false;
    for (const Element& element : header.elements) {
        const bool isVertex = &element == vertexElement;
        const bool isFace = element.name == "face";
        if (isFace && !verticesRead) fail("the face element comes before the vertex element");
        const int listProperty = isFace ? faceIndexProperty(element) : -1;
        for (uint64_t item = 0; item < element.count; ++item) {
            readItem(body, element, listProperty, &values, &list);
            if (isVertex) {
                builder.addVertex(Vec3(float(values[layout.position[0]]),
                                       float(values[layout.position[1]]),
                                       float(values[layout.position[2]])));
            } else if (isFace) {
                builder.addPolygon(list, item);
            }
        }
        verticesRead = verticesRead || isVertex;
    }
    body.expectEnd();
    return builder.take();
}

std::vector<char> readFile(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open mesh " + file.string());
    return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

MeshData readPly(const fs::path& file) {
    const std::vector<char> bytes = readFile(file);
    try {
        return readBody(bytes, readHeader(bytes));
    } catch (const PlyError& e) {
        throw std::runtime_error("mesh " + file.string() + ": malformed PLY: " + e.what());
    }
}

}  // namespace rr
