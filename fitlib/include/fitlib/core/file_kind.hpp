#pragma once
// What kind of text file a reader was handed, from its first line that is not blank or a '#'
// comment, so that a card given as a table or a scene given as a card is named as such in the
// error instead of "invalid JSON" at 1:1 (docs/decisions.md "Inputs: a file of the wrong kind is
// named as such").
#include <string>

namespace fitlib::core {

enum class FileKind { unknown, json, toml, csv };

// json: the line starts with '{' or '['  followed by '{' or '"'; toml: a [table] header or
// `key = value`; csv: a comma-separated line without '='.
FileKind sniff_file_kind(const std::string& text);

// "; it looks like a CSV table, not JSON (...)" when `text` looks like another kind than
// `expected`, else "".
std::string wrong_kind_hint(const std::string& text, FileKind expected);

}  // namespace fitlib::core
