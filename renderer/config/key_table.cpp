#include "config/key_table.h"

namespace rr {

namespace {

const char* kindName(KeyKind kind) {
    switch (kind) {
        case KeyKind::Number:
            return "number";
        case KeyKind::Integer:
            return "integer";
        case KeyKind::Boolean:
            return "boolean";
        case KeyKind::String:
            return "string";
        case KeyKind::Choice:
            return "choice";
        case KeyKind::Colour:
            return "colour";
        case KeyKind::Vector:
            return "vector";
        case KeyKind::Numbers:
            return "numbers";
        case KeyKind::Points:
            return "points";
        case KeyKind::ColourTexture:
            return "colour_texture";
        case KeyKind::NumberTexture:
            return "number_texture";
        case KeyKind::Object:
            return "object";
        case KeyKind::OneOf:
            return "one_of";
        case KeyKind::ListOf:
            return "list_of";
        case KeyKind::MapOf:
            return "map_of";
        case KeyKind::Custom:
            return "custom";
    }
    return "?";
}

bool hasRange(KeyKind kind) {
    switch (kind) {
        case KeyKind::Number:
        case KeyKind::Integer:
        case KeyKind::Colour:
        case KeyKind::Numbers:
        case KeyKind::ColourTexture:
        case KeyKind::NumberTexture:
            return true;
        default:
            return false;
    }
}

nlohmann::json describeRange(const Range& r) {
    nlohmann::json out = nlohmann::json::object();
    if (r.hasLo()) out[r.loOpen ? "exclusive_minimum" : "minimum"] = r.lo;
    if (r.hasHi()) out[r.hiOpen ? "exclusive_maximum" : "maximum"] = r.hi;
    return out;
}

nlohmann::json describeTable(const KeyTable& table) {
    nlohmann::json keys = nlohmann::json::array();
    for (const KeySpec& spec : table.keys)
        keys.push_back(describeKey(spec));
    return {{"meaning", table.meaning}, {"keys", keys}};
}

}  // namespace

nlohmann::json describeKey(const KeySpec& spec) {
    nlohmann::json k = {{"name", spec.name},
                        {"kind", kindName(spec.kind)},
                        {"meaning", spec.meaning},
                        {"required", spec.required()}};
    if (hasRange(spec.kind)) k["range"] = describeRange(spec.range);
    if (!spec.fallback.is_null()) k["default"] = spec.fallback;
    if (!spec.defaultText.empty()) k["default_text"] = spec.defaultText;
    if (!spec.choices.empty()) k["choices"] = spec.choices;
    if (spec.count > 0) k["count"] = spec.count;
    if (!spec.refers.empty()) k["refers"] = spec.refers;
    if (!spec.valueText.empty()) k["value_text"] = spec.valueText;
    if (!spec.schema.is_null()) k["schema"] = spec.schema;
    if (spec.estimandNeutral) k["estimand_neutral"] = true;
    return k;
}

const KeySpec* KeyTable::find(const std::string& key) const {
    for (const KeySpec& spec : keys)
        if (spec.name == key) return &spec;
    return nullptr;
}

const KeyTable* KeyCatalogue::table(const std::string& name) const {
    for (const KeyTable* t : tables)
        if (t->name == name) return t;
    return nullptr;
}

const KeyCatalogue::Category* KeyCatalogue::category(const std::string& name) const {
    for (const Category& c : categories)
        if (c.name == name) return &c;
    return nullptr;
}

const KeyTable* KeyCatalogue::typeTable(const Category& c, const nlohmann::json& object) const {
    std::string type = c.defaultType;
    if (const auto it = object.find("type"); it != object.end() && it->is_string())
        type = it->get<std::string>();
    for (const auto& [name, table] : c.types)
        if (name == type) return table;
    return nullptr;
}

nlohmann::json KeyCatalogue::describe() const {
    nlohmann::json tablesJson = nlohmann::json::object();
    for (const KeyTable* t : tables)
        tablesJson[t->name] = describeTable(*t);
    nlohmann::json categoriesJson = nlohmann::json::object();
    for (const Category& c : categories) {
        nlohmann::json types = nlohmann::json::array();  // in the category's own order
        for (const auto& [name, table] : c.types)
            types.push_back({name, table->name});
        nlohmann::json entry = {{"meaning", c.meaning}, {"types", types}};
        if (c.common) entry["common"] = c.common->name;
        if (!c.defaultType.empty()) entry["default_type"] = c.defaultType;
        categoriesJson[c.name] = entry;
    }
    return {
        {"root", root ? root->name : ""}, {"tables", tablesJson}, {"categories", categoriesJson}};
}

}  // namespace rr
