#pragma once
// Reading JSON files (cards, schedules, surfaces, sidecars) with errors that name the file and
// the line and column (syntax) or the key path (wrong type, number out of range); one helper for
// every reader so that no raw JSON-library message (and no exit 4) reaches the user.
#include <string>

#include <nlohmann/json.hpp>

namespace fitlib::core {

// Parses `text` read from `source`. Syntax errors: InputError at line:column; a number literal
// beyond the double range (≥ 1e309): InputError naming the key path, e.g. parameters[2].value.
nlohmann::json parse_json(const std::string& text, const std::string& source);

// read_file + parse_json.
nlohmann::json load_json(const std::string& path);

// Typed values; an InputError naming `source` and `key` when the type is wrong or a number is not
// finite.
double json_number(const nlohmann::json& value, const std::string& source, const std::string& key);
std::string json_string(const nlohmann::json& value, const std::string& source, const std::string& key);
bool json_bool(const nlohmann::json& value, const std::string& source, const std::string& key);
// A whole number in [lo, hi] (a JSON integer or a float with no fraction).
long long json_integer(const nlohmann::json& value, long long lo, long long hi,
                       const std::string& source, const std::string& key);

}  // namespace fitlib::core
