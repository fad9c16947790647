// Strict reading of one JSON object: typed getters with defaults and range checks, from the
// object's key table (key_table.h), and a final check that rejects keys nobody asked for
// (typos must not be silently ignored).
// Errors are ConfigError with the JSON pointer of the bad value.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "config/config_error.h"
#include "config/key_table.h"
#include "config/range.h"
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

class ObjectReader {
  public:
    // `value` must be a JSON object; `pointer` is its location in the document.
    ObjectReader(const Json& value, std::string pointer);
    // The same, reading through `keys` (key_table.h): see addKeys.
    ObjectReader(const Json& value, std::string pointer, const KeyTable& keys);
    ObjectReader(const ObjectReader&) = delete;
    ObjectReader& operator=(const ObjectReader&) = delete;

    // From now on the object's keys are declared by its tables: the short getters below take
    // their ranges and defaults from there, and asking for a key no table declares is a
    // programming error (std::logic_error), so a reader cannot read what the docs and the
    // schema do not know. A shape reads through its common table and then its type's.
    void addKeys(const KeyTable& keys);

    bool has(const std::string& key) const;
    const std::string& pointer() const { return pointer_; }
    std::string pointerTo(const std::string& key) const;
    [[noreturn]] void fail(const std::string& key, const std::string& message) const;

    // Marks the key as read and returns its raw value (required).
    const Json& raw(const std::string& key);
    const Json* rawOptional(const std::string& key);

    // The declared key's value, checked against its range (choices, count), or its default
    // when absent; a missing key without a default is an error ("missing required key").
    double number(const std::string& key);
    float real(const std::string& key) { return static_cast<float>(number(key)); }
    int64_t integer(const std::string& key);
    bool boolean(const std::string& key);
    std::string string(const std::string& key);
    std::string choice(const std::string& key);
    Rgb colour(const std::string& key);
    Vec3 vector(const std::string& key);
    Vec3d point(const std::string& key);
    std::vector<double> numbers(const std::string& key);
    std::vector<Vec3d> points(const std::string& key);
    // The declaration of a key (for readers that pass its range on, as textures do).
    const KeySpec& spec(const std::string& key) const;

    // Getters with the range and default given by the caller: for values whose range comes
    // from their context (a texture's values take the range of the key that holds the
    // texture) or whose default depends on other keys (a spot's falloff starts at its cone).
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
    std::string getChoice(const std::string& key, const std::vector<std::string>& choices,
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

    // Every declared key read so far with the value used (its default when absent): what an
    // integrator built from this object records as its parameters.
    const Json& values() const { return values_; }

  private:
    // `real`: a real-valued quantity, also held to the magnitude bound (kMinMagnitude,
    // kMaxMagnitude); integers have only their Range.
    double checkedNumber(const Json& v, const std::string& key, Range range, bool real) const;
    // Throws std::logic_error when the reader has tables and none declares `key`.
    void checkDeclared(const std::string& key) const;
    template <class T>
    T noted(const std::string& key, T value);

    const Json& value_;
    std::string pointer_;
    std::vector<const KeyTable*> tables_;
    Json values_ = Json::object();
    std::set<std::string> read_;           // keys whose values were used
    mutable std::set<std::string> known_;  // every key asked about, present or not
};

// JSON pointer escaping (RFC 6901) of a single key.
std::string escapePointerToken(const std::string& key);

}  // namespace rr
