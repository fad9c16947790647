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
    const bool hasLo = lo > -1e299, hasHi = hi < 1e299;
    if (hasLo && hasHi)
        return std::string("in ") + (loOpen ? "(" : "[") + formatNumber(lo) + ", " +
               formatNumber(hi) + (hiOpen ? ")" : "]");
    if (hasLo) return std::string(loOpen ? "> " : ">= ") + formatNumber(lo);
    if (hasHi) return std::string(hiOpen ? "< " : "<= ") + formatNumber(hi);
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

ObjectReader::ObjectReader(const Json& value, std::string pointer)
    : value_(value), pointer_(std::move(pointer)) {
    if (!value_.is_object())
        throw ConfigError(pointer_, "expected an object, got " + typeName(value_));
}

bool ObjectReader::has(const std::string& key) const {
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
    read_.insert(key);
    return value_.at(key);
}

const Json* ObjectReader::rawOptional(const std::string& key) {
    if (!has(key)) return nullptr;
    read_.insert(key);
    return &value_.at(key);
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
    return checkedNumber(raw(key), key, range, /*real=*/true);
}

double ObjectReader::getNumber(const std::string& key, double fallback, Range range) {
    const Json* v = rawOptional(key);
    return v ? checkedNumber(*v, key, range, /*real=*/true) : fallback;
}

int64_t ObjectReader::getInt(const std::string& key, int64_t fallback, Range range) {
    const Json* v = rawOptional(key);
    if (!v) return fallback;
    if (!v->is_number_integer()) fail(key, "expected an integer, got " + typeName(*v));
    return static_cast<int64_t>(checkedNumber(*v, key, range, /*real=*/false));
}

bool ObjectReader::getBool(const std::string& key, bool fallback) {
    const Json* v = rawOptional(key);
    if (!v) return fallback;
    if (!v->is_boolean()) fail(key, "expected true or false, got " + typeName(*v));
    return v->get<bool>();
}

std::string ObjectReader::getString(const std::string& key) {
    const Json& v = raw(key);
    if (!v.is_string()) fail(key, "expected a string, got " + typeName(v));
    return v.get<std::string>();
}

std::string ObjectReader::getString(const std::string& key, const std::string& fallback) {
    return has(key) ? getString(key) : fallback;
}

std::string ObjectReader::getChoice(const std::string& key,
                                    std::initializer_list<const char*> choices,
                                    std::optional<std::string> fallback) {
    if (!has(key) && fallback) return *fallback;
    const std::string s = getString(key);
    std::string list;
    for (const char* c : choices) {
        if (s == c) return s;
        list += (list.empty() ? "" : ", ") + std::string("\"") + c + "\"";
    }
    fail(key, "unknown value \"" + s + "\", expected one of " + list);
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
    return checkedNumbers(raw(key), pointerTo(key), count, range);
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
    return out;
}

Vec3d ObjectReader::getPoint(const std::string& key) {
    const auto v = getNumbers(key, 3);
    return {v[0], v[1], v[2]};
}

Vec3d ObjectReader::getPoint(const std::string& key, const Vec3d& fallback) {
    return has(key) ? getPoint(key) : fallback;
}

Vec3 ObjectReader::getVec3(const std::string& key) {
    const auto v = getNumbers(key, 3);
    return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

Vec3 ObjectReader::getVec3(const std::string& key, const Vec3& fallback) {
    return has(key) ? getVec3(key) : fallback;
}

Rgb ObjectReader::getRgb(const std::string& key, Range range) {
    const Json& v = raw(key);
    if (v.is_number()) {
        const float s = static_cast<float>(checkedNumber(v, key, range, /*real=*/true));
        return Rgb(s);
    }
    if (!v.is_array()) fail(key, "expected a colour: a number or an array of 3 numbers");
    const auto c = getNumbers(key, 3, range);
    return {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2])};
}

Rgb ObjectReader::getRgb(const std::string& key, const Rgb& fallback, Range range) {
    return has(key) ? getRgb(key, range) : fallback;
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
