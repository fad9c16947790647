// Dispatch on the "type" key of a JSON object through a table of builders, with an error
// that lists the known types. Shared by every factory.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <type_traits>

#include "config/json_reader.h"

namespace rr {

template <class T, class... Args>
using TypeTable = std::map<std::string, std::function<std::unique_ptr<T>(ObjectReader&, Args...)>>;

template <class T, class... Args>
std::unique_ptr<T> buildByType(ObjectReader& json, const char* category,
                               const TypeTable<T, Args...>& table,
                               std::type_identity_t<Args>... args) {
    const std::string type = json.getString("type");
    const auto it = table.find(type);
    if (it == table.end()) {
        std::string known;
        for (const auto& entry : table)
            known += (known.empty() ? "\"" : ", \"") + entry.first + "\"";
        json.fail("type", "unknown " + std::string(category) + " type \"" + type +
                              "\", expected one of: " + known);
    }
    std::unique_ptr<T> object = it->second(json, args...);
    json.finish();
    return object;
}

}  // namespace rr
