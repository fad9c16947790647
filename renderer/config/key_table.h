// The keys an object of a scene file takes, declared once per reader: name, kind of value,
// range, default and one line of meaning. The reader reads through its table (ObjectReader
// takes ranges and defaults from it and refuses to read an undeclared key), the integrators'
// parameters() record what was read, and `renderer keys` prints every table, from which
// configs/README.md's key tables and configs/schema/scene.schema.json are generated
// (tests/scene_keys.py checks that both agree with the tables).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "config/range.h"

namespace rr {

enum class KeyKind {
    Number,   // a real number in `range`
    Integer,  // an integer in `range`
    Boolean,
    String,         // any string (a name, a file)
    Choice,         // one of `choices`
    Colour,         // a number (grey) or [r, g, b], each component in `range`
    Vector,         // [x, y, z]
    Numbers,        // an array of exactly `count` numbers in `range`
    Points,         // an array of at least `count` points [x, y, z]
    ColourTexture,  // a colour, or a texture object whose values are held to `range`
    NumberTexture,  // a number, or a texture object whose values are held to `range`
    Object,         // an object read by the table named `refers`
    OneOf,          // an object whose "type" picks its table within the category `refers`
    ListOf,         // an array of such objects
    MapOf,          // an object mapping names to such objects
    Custom,         // anything else: `valueText` says what, `schema` gives its JSON Schema
};

struct KeySpec {
    std::string name;
    KeyKind kind = KeyKind::Number;
    Range range;
    nlohmann::json fallback;  // the default; null: required (unless `optional`)
    bool optional = false;    // absent means something of its own (no default value)
    std::vector<std::string> choices;
    size_t count = 0;
    std::string refers;       // Object: a table; OneOf, ListOf, MapOf: a category
    std::string meaning;      // one line
    std::string valueText;    // docs: the value column, for kinds that cannot say it
    std::string defaultText;  // docs: a default that depends on other keys
    nlohmann::json schema;    // Custom: the value's JSON Schema
    // A key that changes how the scene is sampled, never what the image converges to (seeds,
    // sample counts, samplers, light selection): references key on the rest (estimandOf).
    bool estimandNeutral = false;

    bool required() const { return fallback.is_null() && !optional && defaultText.empty(); }
};

// Builds a KeySpec in one expression: key("alpha").number(Range::open(0, 1)).byDefault(0.5)
// .means("...").
class key {
  public:
    explicit key(std::string name) { spec_.name = std::move(name); }
    key& number(Range r = Range::any()) { return kind(KeyKind::Number, r); }
    key& integer(Range r) { return kind(KeyKind::Integer, r); }
    key& boolean() { return kind(KeyKind::Boolean); }
    key& string() { return kind(KeyKind::String); }
    key& choice(std::vector<std::string> choices) {
        spec_.choices = std::move(choices);
        return kind(KeyKind::Choice);
    }
    key& colour(Range r = Range::nonNegative()) { return kind(KeyKind::Colour, r); }
    key& vector() { return kind(KeyKind::Vector); }
    key& numbers(size_t count, Range r = Range::any()) {
        spec_.count = count;
        return kind(KeyKind::Numbers, r);
    }
    key& points(size_t minCount) {
        spec_.count = minCount;
        return kind(KeyKind::Points);
    }
    key& colourTexture(Range r) { return kind(KeyKind::ColourTexture, r); }
    key& numberTexture(Range r) { return kind(KeyKind::NumberTexture, r); }
    key& object(std::string table) { return refer(KeyKind::Object, std::move(table)); }
    key& oneOf(std::string category) { return refer(KeyKind::OneOf, std::move(category)); }
    key& listOf(std::string category) { return refer(KeyKind::ListOf, std::move(category)); }
    key& mapOf(std::string category) { return refer(KeyKind::MapOf, std::move(category)); }
    key& custom(std::string valueText, nlohmann::json schema) {
        spec_.valueText = std::move(valueText);
        spec_.schema = std::move(schema);
        return kind(KeyKind::Custom);
    }
    key& byDefault(nlohmann::json value) {
        spec_.fallback = std::move(value);
        return *this;
    }
    key& defaultSays(std::string text) {
        spec_.defaultText = std::move(text);
        return *this;
    }
    key& optional() {
        spec_.optional = true;
        return *this;
    }
    key& estimandNeutral() {
        spec_.estimandNeutral = true;
        return *this;
    }
    key& means(std::string meaning) {
        spec_.meaning = std::move(meaning);
        return *this;
    }
    operator KeySpec() const { return spec_; }  // NOLINT: the point of the builder

  private:
    key& kind(KeyKind k, Range r = Range::any()) {
        spec_.kind = k;
        spec_.range = r;
        return *this;
    }
    key& refer(KeyKind k, std::string name) {
        spec_.refers = std::move(name);
        return kind(k);
    }
    KeySpec spec_;
};

// The keys of one kind of object: a table name ("camera", "shape/sphere", "integrator/tais"),
// one line about the object, and its keys in the order the docs list them.
struct KeyTable {
    std::string name;
    std::string meaning;
    std::vector<KeySpec> keys;

    const KeySpec* find(const std::string& key) const;
};

// Every table of the scene format and how objects pick theirs: the root table, the named
// tables, and the categories whose objects pick a table by their "type" (with the keys every
// member takes besides its own).
struct KeyCatalogue {
    struct Category {
        std::string name;
        std::string meaning;
        const KeyTable* common = nullptr;  // keys every member takes (shapes' material, ...)
        std::vector<std::pair<std::string, const KeyTable*>> types;
        std::string defaultType;  // when the "type" key may be left out
    };
    const KeyTable* root = nullptr;
    std::vector<const KeyTable*> tables;
    std::vector<Category> categories;

    const KeyTable* table(const std::string& name) const;
    const Category* category(const std::string& name) const;
    // The table of an object of `category` given its JSON (nullptr: no or unknown "type").
    const KeyTable* typeTable(const Category& category, const nlohmann::json& object) const;
    // The catalogue as JSON, for `renderer keys`.
    nlohmann::json describe() const;
};

// The JSON of one key's declaration (kind, range, default, meaning, ...).
nlohmann::json describeKey(const KeySpec& spec);

}  // namespace rr
