#include "config/json_reader.h"

#include <cmath>
#include <sstream>

namespace rr {

namespace {

std::string typeName(const Json& v) {
    if (v.is_number()) return "a number";
    if (v.is_string()) return "a string";
    if (v.is_boolean()) return "a boolean";
    if (v.is_array()) return "an array";
    if (v.is_object()) return "an object";
    return "null";
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

// See kMinMagnitude/kMaxMagnitude in the header.
bool hasSafeMagnitude(double v) {
    const double a = std::abs(v);
    return a == 0 || (a >= kMinMagnitude && a <= kMaxMagnitude);
}

std::string magnitudeMessage(double v) {
    static_assert(kMinMagnitude == 1e-30 && kMaxMagnitude == 1e10, "update the message");
    return "expected a number of magnitude between 1e-30 and 1e10 (or 0), got " + formatNumber(v);
}

}  // namespace

bool Range::contains(double v) const {
    if (loOpen ? v <= lo : v < lo) return false;
    if (hiOpen ? v >= hi : v > hi) return false;
    return true;
}

std::string Range::describe() const {
    if (hasLo() && hasHi())
        return std::string("in ") + (loOpen ? "(" : "[") + formatNumber(lo) + ", " +
               formatNumber(hi) + (hiOpen ? ")" : "]");
    if (hasLo()) return std::string(loOpen ? "> " : ">= ") + formatNumber(lo);
    if (hasHi()) return std::string(hiOpen ? "< " : "<= ") + formatNumber(hi);
    return "finite";
}

std::string escapePointerToken(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

namespace {

// The JSON of a value read, for values().
Json toJson(double v) {
    return v;
}
Json toJson(int64_t v) {
    return v;
}
Json toJson(bool v) {
    return v;
}
Json toJson(const std::string& v) {
    return v;
}
Json toJson(const Rgb& v) {
    return v.r == v.g && v.g == v.b ? Json(v.r) : Json{v.r, v.g, v.b};
}
Json toJson(const Vec3& v) {
    return {v.x, v.y, v.z};
}
Json toJson(const Vec3d& v) {
    return {v.x, v.y, v.z};
}
Json toJson(const std::vector<double>& v) {
    return v;
}
Json toJson(const std::vector<Vec3d>& points) {
    Json out = Json::array();
    for (const Vec3d& p : points)
        out.push_back(toJson(p));
    return out;
}

}  // namespace

ObjectReader::ObjectReader(const Json& value, std::string pointer)
    : value_(value), pointer_(std::move(pointer)) {
    if (!value_.is_object())
        throw ConfigError(pointer_, "expected an object, got " + typeName(value_));
}

ObjectReader::ObjectReader(const Json& value, std::string pointer, const KeyTable& keys)
    : ObjectReader(value, std::move(pointer)) {
    addKeys(keys);
}

void ObjectReader::addKeys(const KeyTable& keys) {
    tables_.push_back(&keys);
}

void ObjectReader::checkDeclared(const std::string& key) const {
    if (tables_.empty()) return;
    for (const KeyTable* table : tables_)
        if (table->find(key)) return;
    throw std::logic_error("the reader of " + (pointer_.empty() ? std::string("/") : pointer_) +
                           " asked for \"" + key + "\", which its key table (" +
                           tables_.back()->name + ") does not declare");
}

const KeySpec& ObjectReader::spec(const std::string& key) const {
    for (const KeyTable* table : tables_)
        if (const KeySpec* s = table->find(key)) return *s;
    checkDeclared(key);
    throw std::logic_error("the reader of " + pointer_ + " has no key table for \"" + key + "\"");
}

template <class T>
T ObjectReader::noted(const std::string& key, T value) {
    values_[key] = toJson(value);
    return value;
}

bool ObjectReader::has(const std::string& key) const {
    checkDeclared(key);
    known_.insert(key);
    return value_.contains(key);
}

std::string ObjectReader::pointerTo(const std::string& key) const {
    return pointer_ + "/" + escapePointerToken(key);
}

void ObjectReader::fail(const std::string& key, const std::string& message) const {
    throw ConfigError(pointerTo(key), message);
}

const Json& ObjectReader::raw(const std::string& key) {
    if (!has(key)) fail(key, "missing required key");
    return *rawOptional(key);
}

const Json* ObjectReader::rawOptional(const std::string& key) {
    const bool present = has(key);
    if (present) read_.insert(key);
    // A declared value its reader interprets itself (not an object with keys of its own, which
    // has its own reader and values) is recorded as written, or as its default.
    if (!tables_.empty()) {
        const KeySpec& s = spec(key);
        const bool nested = s.kind == KeyKind::Object || s.kind == KeyKind::OneOf ||
                            s.kind == KeyKind::ListOf || s.kind == KeyKind::MapOf;
        if (!nested && (present || !s.fallback.is_null()))
            values_[key] = present ? value_.at(key) : s.fallback;
    }
    return present ? &value_.at(key) : nullptr;
}

double ObjectReader::checkedNumber(const Json& v, const std::string& key, Range range,
                                   bool real) const {
    if (!v.is_number()) fail(key, "expected a number, got " + typeName(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(key, "expected a finite number");
    if (real && !hasSafeMagnitude(d)) fail(key, magnitudeMessage(d));
    if (!range.contains(d))
        fail(key, "expected a number " + range.describe() + ", got " + formatNumber(d));
    return d;
}

double ObjectReader::getNumber(const std::string& key, Range range) {
    return noted(key, checkedNumber(raw(key), key, range, /*real=*/true));
}

double ObjectReader::getNumber(const std::string& key, double fallback, Range range) {
    const Json* v = rawOptional(key);
    return noted(key, v ? checkedNumber(*v, key, range, /*real=*/true) : fallback);
}

int64_t ObjectReader::getInt(const std::string& key, int64_t fallback, Range range) {
    const Json* v = rawOptional(key);
    if (!v) return noted(key, fallback);
    if (!v->is_number_integer()) fail(key, "expected an integer, got " + typeName(*v));
    return noted(key, static_cast<int64_t>(checkedNumber(*v, key, range, /*real=*/false)));
}

bool ObjectReader::getBool(const std::string& key, bool fallback) {
    const Json* v = rawOptional(key);
    if (!v) return noted(key, fallback);
    if (!v->is_boolean()) fail(key, "expected true or false, got " + typeName(*v));
    return noted(key, v->get<bool>());
}

std::string ObjectReader::getString(const std::string& key) {
    const Json& v = raw(key);
    if (!v.is_string()) fail(key, "expected a string, got " + typeName(v));
    return noted(key, v.get<std::string>());
}

std::string ObjectReader::getString(const std::string& key, const std::string& fallback) {
    return has(key) ? getString(key) : noted(key, fallback);
}

std::string ObjectReader::getChoice(const std::string& key, const std::vector<std::string>& choices,
                                    std::optional<std::string> fallback) {
    if (!has(key) && fallback) return noted(key, *fallback);
    const std::string s = getString(key);
    std::string list;
    for (const std::string& c : choices) {
        if (s == c) return s;
        list += (list.empty() ? "" : ", ") + std::string("\"") + c + "\"";
    }
    fail(key, "unknown value \"" + s + "\", expected one of " + list);
}

namespace {

// A declared default as the getters' fallback type.
Rgb rgbOf(const Json& v) {
    if (v.is_number()) return Rgb(v.get<float>());
    return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
}

Vec3 vec3Of(const Json& v) {
    return {v[0].get<float>(), v[1].get<float>(), v[2].get<float>()};
}

}  // namespace

double ObjectReader::number(const std::string& key) {
    const KeySpec& s = spec(key);
    return s.fallback.is_null() ? getNumber(key, s.range)
                                : getNumber(key, s.fallback.get<double>(), s.range);
}

int64_t ObjectReader::integer(const std::string& key) {
    const KeySpec& s = spec(key);
    if (s.fallback.is_null() && !has(key)) fail(key, "missing required key");
    return getInt(key, s.fallback.is_null() ? 0 : s.fallback.get<int64_t>(), s.range);
}

bool ObjectReader::boolean(const std::string& key) {
    const KeySpec& s = spec(key);
    if (s.fallback.is_null() && !has(key)) fail(key, "missing required key");
    return getBool(key, s.fallback.is_null() ? false : s.fallback.get<bool>());
}

std::string ObjectReader::string(const std::string& key) {
    const KeySpec& s = spec(key);
    return s.fallback.is_null() ? getString(key) : getString(key, s.fallback.get<std::string>());
}

std::string ObjectReader::choice(const std::string& key) {
    const KeySpec& s = spec(key);
    return getChoice(
        key, s.choices,
        s.fallback.is_null() ? std::nullopt : std::optional(s.fallback.get<std::string>()));
}

Rgb ObjectReader::colour(const std::string& key) {
    const KeySpec& s = spec(key);
    return s.fallback.is_null() ? getRgb(key, s.range) : getRgb(key, rgbOf(s.fallback), s.range);
}

Vec3 ObjectReader::vector(const std::string& key) {
    const KeySpec& s = spec(key);
    return s.fallback.is_null() ? getVec3(key) : getVec3(key, vec3Of(s.fallback));
}

Vec3d ObjectReader::point(const std::string& key) {
    const KeySpec& s = spec(key);
    if (s.fallback.is_null()) return getPoint(key);
    const auto& f = s.fallback;
    return getPoint(key, Vec3d{f[0].get<double>(), f[1].get<double>(), f[2].get<double>()});
}

std::vector<double> ObjectReader::numbers(const std::string& key) {
    const KeySpec& s = spec(key);
    if (!has(key) && !s.fallback.is_null())
        return noted(key, s.fallback.get<std::vector<double>>());
    return getNumbers(key, s.count, s.range);
}

std::vector<Vec3d> ObjectReader::points(const std::string& key) {
    return getPointArray(key, spec(key).count);
}

namespace {

// The elements of `v`, an array of `count` real numbers at JSON pointer `at`.
std::vector<double> checkedNumbers(const Json& v, const std::string& at, size_t count,
                                   Range range) {
    if (!v.is_array() || v.size() != count)
        throw ConfigError(at, "expected an array of " + std::to_string(count) + " numbers");
    std::vector<double> out;
    for (size_t i = 0; i < count; ++i) {
        const Json& e = v[i];
        const std::string element = at + "/" + std::to_string(i);
        if (!e.is_number() || !std::isfinite(e.get<double>()))
            throw ConfigError(element, "expected a finite number, got " + typeName(e));
        const double d = e.get<double>();
        if (!hasSafeMagnitude(d)) throw ConfigError(element, magnitudeMessage(d));
        if (!range.contains(d))
            throw ConfigError(element,
                              "expected a number " + range.describe() + ", got " + formatNumber(d));
        out.push_back(d);
    }
    return out;
}

}  // namespace

std::vector<double> ObjectReader::getNumbers(const std::string& key, size_t count, Range range) {
    return noted(key, checkedNumbers(raw(key), pointerTo(key), count, range));
}

std::vector<Vec3d> ObjectReader::getPointArray(const std::string& key, size_t minCount) {
    const Json& v = raw(key);
    if (!v.is_array() || v.size() < minCount)
        fail(key,
             "expected an array of at least " + std::to_string(minCount) + " points [x, y, z]");
    std::vector<Vec3d> out;
    for (size_t i = 0; i < v.size(); ++i) {
        const auto c =
            checkedNumbers(v[i], pointerTo(key) + "/" + std::to_string(i), 3, Range::any());
        out.push_back({c[0], c[1], c[2]});
    }
    return noted(key, out);
}

Vec3d ObjectReader::getPoint(const std::string& key) {
    const auto v = getNumbers(key, 3);
    return {v[0], v[1], v[2]};
}

Vec3d ObjectReader::getPoint(const std::string& key, const Vec3d& fallback) {
    return has(key) ? getPoint(key) : noted(key, fallback);
}

Vec3 ObjectReader::getVec3(const std::string& key) {
    const auto v = getNumbers(key, 3);
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

Vec3 ObjectReader::getVec3(const std::string& key, const Vec3& fallback) {
    return has(key) ? getVec3(key) : noted(key, fallback);
}

Rgb ObjectReader::getRgb(const std::string& key, Range range) {
    const Json& v = raw(key);
    if (v.is_number()) {
        const float s = static_cast<float>(checkedNumber(v, key, range, /*real=*/true));
        return noted(key, Rgb(s));
    }
    if (!v.is_array()) fail(key, "expected a colour: a number or an array of 3 numbers");
    const auto c = getNumbers(key, 3, range);
    return noted(key,
                 Rgb{static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])});
}

Rgb ObjectReader::getRgb(const std::string& key, const Rgb& fallback, Range range) {
    return has(key) ? getRgb(key, range) : noted(key, fallback);
}

void ObjectReader::finish() const {
    for (const auto& item : value_.items()) {
        if (read_.count(item.key())) continue;
        std::string accepted;
        for (const auto& k : known_)
            accepted += (accepted.empty() ? "" : ", ") + k;
        throw ConfigError(
            pointerTo(item.key()),
            "unknown key" + (accepted.empty() ? std::string(", this object takes no keys")
                                              : ", expected one of: " + accepted));
    }
}

}  // namespace rr
