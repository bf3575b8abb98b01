#include "fitlib/core/file_kind.hpp"

#include <sstream>

namespace fitlib::core {
namespace {

std::string first_meaningful_line(const std::string& text) {
  std::istringstream in(text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? text.substr(3) : text);
  for (std::string line; std::getline(in, line);) {
    const auto start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos || line[start] == '#') continue;
    const auto end = line.find_last_not_of(" \t\r");
    return line.substr(start, end - start + 1);
  }
  return "";
}

const char* what_it_is(FileKind k) {
  switch (k) {
    case FileKind::json: return "a JSON document (a card, a surface, a schedule or a summary)";
    case FileKind::toml: return "a TOML file (a scene, a sweep or a schedule)";
    case FileKind::csv: return "a CSV table";
    default: return "";
  }
}

const char* expected_name(FileKind k) {
  switch (k) {
    case FileKind::json: return "JSON";
    case FileKind::toml: return "TOML";
    case FileKind::csv: return "a table";
    default: return "";
  }
}

}  // namespace

FileKind sniff_file_kind(const std::string& text) {
  const std::string line = first_meaningful_line(text);
  if (line.empty()) return FileKind::unknown;
  if (line[0] == '{') return FileKind::json;
  if (line[0] == '[') {  // a JSON array of objects or strings, or a TOML [table] header
    const auto next = line.find_first_not_of(" \t", 1);
    return next != std::string::npos && (line[next] == '{' || line[next] == '"') ? FileKind::json : FileKind::toml;
  }
  if (line.find('=') != std::string::npos) return FileKind::toml;
  if (line.find(',') != std::string::npos) return FileKind::csv;
  return FileKind::unknown;
}

std::string wrong_kind_hint(const std::string& text, FileKind expected) {
  const FileKind seen = sniff_file_kind(text);
  if (seen == FileKind::unknown || seen == expected) return "";
  return std::string("; it looks like ") + what_it_is(seen) + ", not " + expected_name(expected);
}

}  // namespace fitlib::core
