// Dispatch on the "type" key of a JSON object through a table of builders, with an error
// that lists the known types. Shared by every factory.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "config/json_reader.h"

namespace rr {

template <class T, class... Args>
using TypeTable = std::map<std::string, std::function<std::unique_ptr<T>(ObjectReader&, Args...)>>;

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
    std::unique_ptr<T> object = entryByType(json, category, table)(json, args...);
    json.finish();
    return object;
}

}  // namespace rr
