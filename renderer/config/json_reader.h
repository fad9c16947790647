// Strict reading of one JSON object: typed getters with defaults and range checks, and a
// final check that rejects keys nobody asked for (typos must not be silently ignored).
// Errors are ConfigError with the JSON pointer of the bad value.
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "config/config_error.h"
#include "math/rgb.h"
#include "math/vector.h"

namespace rr {

using Json = nlohmann::json;

// Every real-valued number in a scene (not the integers: they have their own Range) must be 0
// or have a magnitude in [kMinMagnitude, kMaxMagnitude]. Scene values are stored in single
// precision: the upper bound keeps products such as areas, powers and squared distances
// finite in float (no inf/NaN) and ray offsets, which scale with coordinates, meaningful; the
// lower bound rejects values that would silently become 0 (or denormal) in float, while
// accepting round-off leftovers such as 1e-17 in exported matrices.
inline constexpr double kMinMagnitude = 1e-30;
inline constexpr double kMaxMagnitude = 1e10;

// Bounds for numbers; open or closed at each end.
struct Range {
    double lo = -1e300, hi = 1e300;
    bool loOpen = false, hiOpen = false;

    static Range any() { return {}; }
    static Range positive() { return {0, 1e300, true, false}; }
    static Range nonNegative() { return {0, 1e300, false, false}; }
    static Range unit() { return {0, 1, false, false}; }  // [0, 1]
    static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
    static Range open(double lo, double hi) { return {lo, hi, true, true}; }
    static Range atLeast(double lo) { return {lo, 1e300, false, false}; }

    bool contains(double v) const;
    std::string describe() const;
};

class ObjectReader {
  public:
    // `value` must be a JSON object; `pointer` is its location in the document.
    ObjectReader(const Json& value, std::string pointer);
    ObjectReader(const ObjectReader&) = delete;
    ObjectReader& operator=(const ObjectReader&) = delete;

    bool has(const std::string& key) const;
    const std::string& pointer() const { return pointer_; }
    std::string pointerTo(const std::string& key) const;
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;

    // Marks the key as read and returns its raw value (required).
    const Json& raw(const std::string& key);
    const Json* rawOptional(const std::string& key);

    double getNumber(const std::string& key, Range range = Range::any());
    double getNumber(const std::string& key, double fallback, Range range = Range::any());
    float getFloat(const std::string& key, Range range = Range::any()) {
        return static_cast<float>(getNumber(key, range));
    }
    float getFloat(const std::string& key, float fallback, Range range = Range::any()) {
        return static_cast<float>(getNumber(key, fallback, range));
    }
    int64_t getInt(const std::string& key, int64_t fallback, Range range = Range::any());
    bool getBool(const std::string& key, bool fallback);
    std::string getString(const std::string& key);
    std::string getString(const std::string& key, const std::string& fallback);
    // A string that must be one of `choices`.
    std::string getChoice(const std::string& key, std::initializer_list<const char*> choices,
                          std::optional<std::string> fallback = std::nullopt);
    Vec3 getVec3(const std::string& key);
    Vec3 getVec3(const std::string& key, const Vec3& fallback);
    // A colour: a number (grey) or an array of three; each component checked against range.
    Rgb getRgb(const std::string& key, Range range = Range::nonNegative());
    Rgb getRgb(const std::string& key, const Rgb& fallback, Range range = Range::nonNegative());
    std::vector<double> getNumbers(const std::string& key, size_t count,
                                   Range range = Range::any());
    // A position [x, y, z], kept in double for the move into rendering space.
    Vec3d getPoint(const std::string& key);
    Vec3d getPoint(const std::string& key, const Vec3d& fallback);
    // An array of at least `minCount` positions [x, y, z].
    std::vector<Vec3d> getPointArray(const std::string& key, size_t minCount);

    // Throws for any key that was not read: call after reading everything.
    void finish() const;

  private:
    // `real`: a real-valued quantity, also held to the magnitude bound (kMinMagnitude,
    // kMaxMagnitude); integers have only their Range.
    double checkedNumber(const Json& v, const std::string& key, Range range, bool real) const;

    const Json& value_;
    std::string pointer_;
    std::set<std::string> read_;           // keys whose values were used
    mutable std::set<std::string> known_;  // every key asked about, present or not
};

// JSON pointer escaping (RFC 6901) of a single key.
std::string escapePointerToken(const std::string& key);

}  // namespace rr
