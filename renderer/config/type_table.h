// Dispatch on the "type" key of a JSON object through a table of builders, each with the key
// table of its type, with an error that lists the known types. Shared by every factory.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "config/json_reader.h"

namespace rr {

template <class T, class... Args>
struct TypeEntry {
    std::function<std::unique_ptr<T>(ObjectReader&, Args...)> build;
    const KeyTable* keys;  // the type's own keys
};

template <class T, class... Args>
using TypeTable = std::map<std::string, TypeEntry<T, Args...>>;

// The "type" key every dispatched object has.
inline const KeyTable& typeKeyTable() {
    static const KeyTable table{"type", "", {key("type").string().means("the object's type")}};
    return table;
}

// "a", "b", "c": names listed in a message.
inline std::string quotedNames(const std::vector<std::string>& names) {
    std::string list;
    for (const std::string& name : names)
        list += (list.empty() ? "\"" : ", \"") + name + "\"";
    return list;
}

// The entry of `table` (any map from type names) named by the object's "type" key; an error
// listing the known types when there is none.
template <class Table>
const typename Table::mapped_type& entryByType(ObjectReader& json, const char* category,
                                               const Table& table) {
    json.addKeys(typeKeyTable());
    const std::string type = json.getString("type");
    const auto it = table.find(type);
    if (it == table.end()) {
        std::vector<std::string> known;
        for (const auto& entry : table)
            known.push_back(entry.first);
        json.fail("type", "unknown " + std::string(category) + " type \"" + type +
                              "\", expected one of: " + quotedNames(known));
    }
    return it->second;
}

template <class T, class... Args>
std::unique_ptr<T> buildByType(ObjectReader& json, const char* category,
                               const TypeTable<T, Args...>& table,
                               std::type_identity_t<Args>... args) {
    const TypeEntry<T, Args...>& entry = entryByType(json, category, table);
    json.addKeys(*entry.keys);
    std::unique_ptr<T> object = entry.build(json, args...);
    json.finish();
    return object;
}

// Each type's name and key table (any map whose entries have `keys`), for the catalogue.
template <class Table>
std::vector<std::pair<std::string, const KeyTable*>> typeKeys(const Table& table) {
    std::vector<std::pair<std::string, const KeyTable*>> types;
    for (const auto& [name, entry] : table)
        types.emplace_back(name, entry.keys);
    return types;
}

}  // namespace rr
