// Named numeric columns of a CSV with a header row, for surface fitting (docs/formats.md §1 conventions).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/surface/fit.hpp"

namespace fitlib::surface {
namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  std::string field = text.substr(first, last - first + 1);
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"')
    field = field.substr(1, field.size() - 2);
  return field;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string::npos ? std::string::npos
                                                                        : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

// Field index of each x column, then of y, in the header (whose names must be unique).
std::vector<int> wanted_fields(const std::vector<std::string>& header,
                               const std::vector<std::string>& x_columns,
                               const std::string& y_column, const std::string& path,
                               int line_number) {
  for (std::size_t i = 0; i < header.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (header[i] == header[j])
        throw core::InputError("duplicate column '" + header[i] + "' in the header", path,
                               line_number, static_cast<int>(i + 1));
  std::vector<std::string> names = x_columns;
  names.push_back(y_column);
  std::vector<int> wanted;
  for (const auto& name : names) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) {
      std::string available;
      for (const auto& h : header) available += (available.empty() ? "" : ", ") + h;
      throw core::InputError("no column '" + name + "' (the header has: " + available + ")",
                             path, line_number, 0);
    }
    wanted.push_back(static_cast<int>(it - header.begin()));
  }
  return wanted;
}

// Appends the wanted fields of one data row to values, each a finite number.
void read_row(const std::vector<std::string>& fields, const std::vector<std::string>& header,
              const std::vector<int>& wanted, const std::string& path, int line_number,
              std::vector<double>& values) {
  if (fields.size() != header.size())
    throw core::InputError("the row has " + std::to_string(fields.size()) +
                               " fields but the header has " + std::to_string(header.size()),
                           path, line_number, static_cast<int>(std::min(fields.size(), header.size()) + 1));
  for (const int w : wanted) {
    const std::string& field = fields[static_cast<std::size_t>(w)];
    const std::string& name = header[static_cast<std::size_t>(w)];
    char* stop = nullptr;
    errno = 0;
    const double v = std::strtod(field.c_str(), &stop);
    if (field.empty() || *stop != '\0')
      throw core::InputError("'" + field + "' in column '" + name + "' is not a number", path,
                             line_number, w + 1);
    if (!std::isfinite(v))
      throw core::InputError("column '" + name + "' holds a non-finite value", path, line_number,
                             w + 1);
    values.push_back(v);
  }
}

// Rows of (x_1 … x_n, y) values into the sample matrix and vector.
void fill_samples(const std::vector<double>& values, std::size_t rows, std::size_t n,
                  SampleSet& data) {
  data.x.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(n));
  data.y.resize(static_cast<Eigen::Index>(rows));
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t k = 0; k < n; ++k)
      data.x(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k)) = values[r * (n + 1) + k];
    data.y[static_cast<Eigen::Index>(r)] = values[r * (n + 1) + n];
  }
}

}  // namespace

SampleSet read_sample_columns(const std::string& path, const std::vector<std::string>& x_columns,
                              const std::string& y_column) {
  std::string text = core::read_file(path);
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);

  SampleSet data;
  data.source = path;
  std::vector<std::string> header;
  std::vector<int> wanted;  // field index of each x column, then y
  std::vector<double> values;
  std::size_t rows = 0;
  int line_number = 0;
  std::size_t position = 0;
  while (position <= text.size()) {
    auto end = text.find('\n', position);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(position, end - position);
    position = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string stripped = trim(line);
    if (stripped.empty() || stripped[0] == '#') {
      if (end == text.size()) break;
      continue;
    }
    const auto fields = split(line);
    if (header.empty()) {
      header = fields;
      wanted = wanted_fields(header, x_columns, y_column, path, line_number);
      data.column_of_axis.assign(wanted.begin(), wanted.end() - 1);
      for (auto& c : data.column_of_axis) ++c;
      data.column_of_y = wanted.back() + 1;
    } else {
      read_row(fields, header, wanted, path, line_number, values);
      data.line_of_row.push_back(line_number);
      ++rows;
    }
    if (end == text.size()) break;
  }
  if (header.empty()) throw core::InputError("no header row", path, line_number, 0);
  if (rows == 0) throw core::InputError("no data rows", path, line_number, 0);
  fill_samples(values, rows, x_columns.size(), data);
  return data;
}

}  // namespace fitlib::surface
