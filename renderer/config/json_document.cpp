#include "config/json_document.h"

#include <charconv>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

namespace rr {

namespace fs = std::filesystem;

namespace {

// Parses `text`, rejecting duplicate keys in any object (nlohmann keeps the last one silently):
// a ConfigError at `base` + the JSON pointer of the duplicate. The parser callback sees the
// document as a stream of events; a stack of the open containers, each with its current
// element index (arrays) or the keys seen so far and the current key (objects), gives the
// pointer of every key.
Json parseRejectingDuplicateKeys(const std::string& text, const std::string& base,
                                 bool ignoreComments) {
    struct Container {
        bool isArray = false;
        size_t index = 0;            // arrays: index of the element being parsed
        std::set<std::string> keys;  // objects: keys seen so far
        std::string key;             // objects: the key of the value being parsed
    };
    std::vector<Container> containers;
    auto pointerOfCurrent = [&] {
        std::string pointer = base;
        for (const Container& c : containers)
            pointer += "/" + (c.isArray ? std::to_string(c.index) : escapePointerToken(c.key));
        return pointer;
    };
    auto elementDone = [&] {
        if (!containers.empty() && containers.back().isArray) ++containers.back().index;
    };
    const Json::parser_callback_t callback = [&](int, Json::parse_event_t event, Json& parsed) {
        switch (event) {
            case Json::parse_event_t::object_start:
            case Json::parse_event_t::array_start:
                containers.push_back({event == Json::parse_event_t::array_start, 0, {}, {}});
                break;
            case Json::parse_event_t::object_end:
            case Json::parse_event_t::array_end:
                containers.pop_back();
                elementDone();
                break;
            case Json::parse_event_t::key: {
                Container& object = containers.back();
                object.key = parsed.get<std::string>();
                if (!object.keys.insert(object.key).second)
                    throw ConfigError(pointerOfCurrent(), "duplicate key");
                break;
            }
            case Json::parse_event_t::value:
                elementDone();
                break;
        }
        return true;
    };
    return Json::parse(text, callback, /*allow_exceptions=*/true, ignoreComments);
}

}  // namespace

Json parseSceneText(const std::string& text, const std::string& sourceName) {
    try {
        return parseRejectingDuplicateKeys(text, "", /*ignoreComments=*/true);
    } catch (const Json::parse_error& e) {
        // Convert nlohmann's byte offset into a line and column.
        size_t line = 1, column = 1;
        for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
            if (text[i] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        throw ConfigError("", "malformed JSON in " + sourceName + " at line " +
                                  std::to_string(line) + ", column " + std::to_string(column));
    }
}

std::string readSceneText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ConfigError("", "cannot open scene file " + file.string());
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

Json readSceneFile(const fs::path& file) {
    return parseSceneText(readSceneText(file), file.string());
}

void applyOverride(Json& document, const std::string& assignment) {
    const size_t eq = assignment.find('=');
    if (eq == std::string::npos || assignment.empty() || assignment[0] != '/')
        throw ConfigError("", "--set expects /json/pointer=value, got \"" + assignment + "\"");
    const std::string pointerText = assignment.substr(0, eq);
    const std::string valueText = assignment.substr(eq + 1);
    Json value;
    try {
        value = parseRejectingDuplicateKeys(valueText, pointerText, /*ignoreComments=*/false);
    } catch (const Json::parse_error&) {
        value = valueText;  // bare words are strings: --set /integrator/type=path
    }
    try {
        const Json::json_pointer pointer(pointerText);
        if (!document.contains(pointer.parent_pointer()))
            throw ConfigError(
                pointerText,
                "--set: the parent " + pointer.parent_pointer().to_string() + " does not exist");
        Json& parent = document[pointer.parent_pointer()];
        if (parent.is_array()) {
            const std::string last = pointer.back();
            size_t index = 0;
            const char* end = last.data() + last.size();
            const auto [stop, ec] = std::from_chars(last.data(), end, index);
            // from_chars takes digits only (no sign, no space) and reports overflow.
            if (last.empty() || ec != std::errc() || stop != end || index >= parent.size())
                throw ConfigError(pointerText, "--set: not an existing array index");
        } else if (!parent.is_object()) {
            throw ConfigError(pointerText, "--set: the parent is neither an object nor an array");
        }
        document[pointer] = value;
    } catch (const Json::exception& e) {
        throw ConfigError(pointerText,
                          std::string("--set: invalid JSON pointer (") + e.what() + ")");
    }
}

}  // namespace rr
