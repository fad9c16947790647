// Scene documents as JSON: parsing that rejects duplicate keys (nlohmann keeps the last one
// silently) and reports malformed text by line and column, and the command line's
// `--set /json/pointer=value` assignments. Errors are ConfigError naming the JSON pointer.
#pragma once

#include <filesystem>
#include <string>

#include "config/json_reader.h"

namespace rr {

// The text of a scene file; ConfigError when it cannot be opened.
std::string readSceneText(const std::filesystem::path& file);

// Parses JSON text (comments allowed); malformed input is a ConfigError at "/" naming line and
// column, a duplicate key a ConfigError at its pointer.
Json parseSceneText(const std::string& text, const std::string& sourceName);
Json readSceneFile(const std::filesystem::path& file);

// Applies `--set /json/pointer=value`: value is parsed as JSON, or taken as a string if it
// is not valid JSON. The parent of the pointer must exist.
void applyOverride(Json& document, const std::string& assignment);

}  // namespace rr
