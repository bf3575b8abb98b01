#pragma once
// Small CSV building blocks shared by the dynamic-test table and the waveform reader.
// Lines and fields are split here (UTF-8 BOM stripped, CRLF handled): both formats have optional
// and alternative columns, which fast-cpp-csv-parser's io::CSVReader (fixed column count known at
// compile time) cannot express, and its io::LineReader allocates 48 MiB per file.
#include <optional>
#include <string>
#include <vector>

#include "fitlib/core/test_condition.hpp"

namespace fitlib::data {

struct CsvLine {
  int number = 0;    // 1-based line in the file
  std::string text;  // without the line end
};

// All lines of `bytes` (the file's content). Throws InputError(file, line) for a NUL byte.
std::vector<CsvLine> split_csv_lines(const std::string& bytes, const std::string& file_name);

// True for lines that carry no data: blank (spaces only) or starting with `#`.
bool is_blank_or_comment(const std::string& text);

// The next line with data at or after `next` (which moves past it); null at the end.
const CsvLine* next_content_line(const std::vector<CsvLine>& lines, std::size_t& next);

// The first line with data at or after `next` (which moves past it): a file's header row;
// InputError "no header row (empty file)" at line 1 when there is none.
const CsvLine& header_line(const std::vector<CsvLine>& lines, std::size_t& next, const std::string& file_name);

// The fields of the first line with data of `bytes`; empty when there is none or it does not
// split (for the readers' looks_like_* sniffers).
std::vector<std::string> first_content_fields(const std::string& bytes);

// Fields of one line: split at commas, spaces and tabs around each field trimmed; a field may be
// double-quoted ("a, b"; "" is a literal quote). Throws InputError for an unterminated quote.
std::vector<std::string> split_csv_fields(const std::string& text, const std::string& file_name,
                                          int line);

// "" for an ordinary column name; for one holding ';' or a tab (a whole header that was not
// split: a semicolon- or tab-separated export), a clause saying how fitlib reads tables; for the
// first "column" of a JSON document or a TOML file, a clause naming what the file looks like. To
// append to an "unknown column" message.
std::string unknown_column_hint(const std::string& column_name);

// A finite number filling the whole field (C locale; a leading '+' is allowed). Throws
// InputError(file, line, column) naming `what` for empty text, a non-number, NaN or Inf.
double parse_csv_number(const std::string& text, const std::string& what,
                        const std::string& file_name, int line, int column);

// Text of `value` that reads back to the same double (core::format_number, shortest round trip).
std::string format_exact(double value);

// Quotes a label for CSV output when it holds a comma, quote or surrounding space.
std::string quote_csv_field(const std::string& text);

constexpr const char* kModeLabels = "shear, uniaxial, tension, compression or bulk";

// Orientation labels of a test (formats.md §1), shared by the table and the waveform reader.
constexpr const char* kOrientationLabels = "11, 22, 33, 12, 13, 23, 3232 or 2332";
bool is_known_orientation(const std::string& label);

}  // namespace fitlib::data
