#pragma once
// JSON text → document with parse errors placed at file, line and column (nlohmann reports a
// byte offset only).
#include <string>

#include <nlohmann/json.hpp>

namespace fitlib::core {

// Parses `text`; InputError("invalid JSON", file, line, column) when it is not JSON.
nlohmann::json parse_json(const std::string& text, const std::string& file_name);

}  // namespace fitlib::core
