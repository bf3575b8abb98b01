#include "fitlib/core/toml_limits.hpp"

#include <algorithm>

#include "fitlib/core/error.hpp"

namespace fitlib::core {

// A scan that knows just enough TOML to skip strings and comments: brackets and dots elsewhere
// are structure (nesting, dotted keys). Values with dots (1.5, dates) have at most two in a row.
void check_toml_limits(const std::string& text, const std::string& source) {
  if (text.size() > kTomlMaxBytes)
    throw InputError("file larger than " + std::to_string(kTomlMaxBytes) +
                         " bytes (a scene or schedule is a few kB)",
                     source);
  int line = 1, column = 0, depth = 0, dots = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    ++column;
    if (c == '\n') {
      ++line;
      column = 0;
      dots = 0;
    } else if (c == '#') {
      while (i + 1 < text.size() && text[i + 1] != '\n') ++i;
    } else if (c == '"' || c == '\'') {
      const bool multi = text.compare(i, 3, std::string(3, c)) == 0;
      const std::string close = multi ? std::string(3, c) : std::string(1, c);
      std::size_t j = i + close.size();
      for (; j < text.size() && text.compare(j, close.size(), close) != 0; ++j) {
        if (c == '"' && text[j] == '\\') ++j;
        if (j < text.size() && text[j] == '\n') {
          if (!multi) break;  // unterminated: toml++ reports it
          ++line;
          column = 0;
        }
      }
      const bool unterminated_line = !multi && j < text.size() && text[j] == '\n';
      i = unterminated_line ? j - 1 : std::min(text.size(), j + close.size()) - 1;
    } else if (c == '[' || c == '{') {
      if (++depth > kTomlMaxNesting)
        throw InputError("nested deeper than " + std::to_string(kTomlMaxNesting) + " levels",
                         source, line, column);
      dots = 0;
    } else if (c == ']' || c == '}') {
      --depth;
      dots = 0;
    } else if (c == '.') {
      if (++dots > kTomlMaxDottedSegments)
        throw InputError("dotted key with more than " + std::to_string(kTomlMaxDottedSegments) +
                             " parts",
                         source, line, column);
    } else if (c == '=' || c == ',') {
      dots = 0;
    }
  }
}

}  // namespace fitlib::core
