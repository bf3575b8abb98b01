#include "fitlib/data/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/file_kind.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::data {

std::vector<CsvLine> split_csv_lines(const std::string& bytes, const std::string& file_name) {
  const auto nul = bytes.find('\0');
  if (nul != std::string::npos) {
    const int line = 1 + static_cast<int>(std::count(bytes.begin(), bytes.begin() + nul, '\n'));
    throw core::InputError("NUL byte: not a text file", file_name, line);
  }
  // Split here (fast-cpp-csv-parser's LineReader allocated 3 x 16 MiB per file): a UTF-8 BOM is
  // dropped, "\r\n" and "\n" end lines, a last line without an end still counts.
  std::vector<CsvLine> lines;
  std::size_t begin = bytes.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  int number = 0;
  while (begin < bytes.size()) {
    std::size_t end = bytes.find('\n', begin);
    if (end == std::string::npos) end = bytes.size();
    std::size_t stop = end;
    if (stop > begin && bytes[stop - 1] == '\r') --stop;
    lines.push_back({++number, bytes.substr(begin, stop - begin)});
    begin = end + 1;
  }
  return lines;
}

bool is_blank_or_comment(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  return first == std::string::npos || text[first] == '#';
}

std::string unknown_column_hint(const std::string& column_name) {
  if (const std::string kind = core::wrong_kind_hint(column_name, core::FileKind::csv); !kind.empty()) return kind;
  const bool semicolon = column_name.find(';') != std::string::npos;
  if (!semicolon && column_name.find('\t') == std::string::npos) return "";
  return std::string("; the name holds ") + (semicolon ? "';'" : "a tab") +
         ": fitlib reads comma-separated tables with '.' as the decimal point (save the export as CSV with commas)";
}

std::vector<std::string> split_csv_fields(const std::string& text, const std::string& file_name,
                                          int line) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  const auto skip_space = [&] {
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
  };
  for (;;) {
    skip_space();
    std::string field;
    if (i < text.size() && text[i] == '"') {
      const int column = static_cast<int>(fields.size()) + 1;
      ++i;
      for (;;) {
        if (i >= text.size()) throw core::InputError("unterminated quote", file_name, line, column);
        if (text[i] == '"') {
          if (i + 1 < text.size() && text[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          ++i;
          break;
        }
        field += text[i++];
      }
      skip_space();
      if (i < text.size() && text[i] != ',')
        throw core::InputError("text after closing quote", file_name, line, column);
    } else {
      const auto end = text.find(',', i);
      field = text.substr(i, end == std::string::npos ? std::string::npos : end - i);
      const auto last = field.find_last_not_of(" \t");
      field.erase(last == std::string::npos ? 0 : last + 1);
      i = end == std::string::npos ? text.size() : end;
    }
    // A control character (other than tab) is no text: a stray CR would not survive writing
    // and reading back (fuzz_table finding, docs/reliability.md).
    const auto control = std::find_if(field.begin(), field.end(), [](char c) {
      return static_cast<unsigned char>(c) < 0x20 && c != '\t';
    });
    if (control != field.end())
      throw core::InputError("control character " + std::to_string(static_cast<int>(*control)) + " in field",
                             file_name, line, static_cast<int>(fields.size()) + 1);
    fields.push_back(std::move(field));
    if (i >= text.size()) break;
    ++i;  // the comma
  }
  return fields;
}

double parse_csv_number(const std::string& text, const std::string& what,
                        const std::string& file_name, int line, int column) {
  if (text.empty()) throw core::InputError("empty " + what, file_name, line, column);
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  if (*begin == '+') ++begin;
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec == std::errc::result_out_of_range)
    throw core::InputError(what + " '" + text + "' is out of range", file_name, line, column);
  if (ec != std::errc() || ptr != end)
    throw core::InputError(what + " '" + text + "' is not a number", file_name, line, column);
  if (!std::isfinite(value))
    throw core::InputError(what + " is " + text + " (NaN/Inf not allowed)", file_name, line,
                           column);
  return value;
}

std::string format_exact(double value) { return core::format_number(value); }

std::string quote_csv_field(const std::string& text) {
  const bool needs_quotes = text.find_first_of(",\"") != std::string::npos ||
                            (!text.empty() && (text.front() == ' ' || text.back() == ' ' ||
                                               text.front() == '#'));
  if (!needs_quotes) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

bool is_known_orientation(const std::string& label) {
  static const char* kOrientations[] = {"11", "22", "33", "12", "13", "23", "3232", "2332"};
  return std::find(std::begin(kOrientations), std::end(kOrientations), label) !=
         std::end(kOrientations);
}

const CsvLine* next_content_line(const std::vector<CsvLine>& lines, std::size_t& next) {
  while (next < lines.size() && is_blank_or_comment(lines[next].text)) ++next;
  return next < lines.size() ? &lines[next++] : nullptr;
}

const CsvLine& header_line(const std::vector<CsvLine>& lines, std::size_t& next, const std::string& file_name) {
  const CsvLine* header = next_content_line(lines, next);
  if (!header) throw core::InputError("no header row (empty file)", file_name, 1);
  return *header;
}

std::vector<std::string> first_content_fields(const std::string& bytes) {
  try {
    const auto lines = split_csv_lines(bytes, "");
    std::size_t next = 0;
    const CsvLine* first = next_content_line(lines, next);
    return first ? split_csv_fields(first->text, "", first->number) : std::vector<std::string>{};
  } catch (const core::InputError&) {
    return {};
  }
}

}  // namespace fitlib::data
