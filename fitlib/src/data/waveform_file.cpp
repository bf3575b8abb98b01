// Reading a waveform record (formats.md §2): the signals CSV, its `# key = value` metadata lines
// and, through specimen_keys, the JSON sidecar.
#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/csv.hpp"
#include "fitlib/data/waveform.hpp"
#include "specimen_keys.hpp"

namespace fitlib::data {
namespace {

using core::InputError;

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// `# key = value` with key an identifier ([A-Za-z_][A-Za-z0-9_]*); other comments are free text.
// A plain scan, linear in the line length (a regular expression recursed per character).
bool parse_metadata_line(const std::string& text, std::string& key, std::string& value) {
  const auto is_start = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; };
  const auto is_part = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  const auto skip_space = [&](std::size_t i) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    return i;
  };
  std::size_t i = skip_space(0);
  if (i == text.size() || text[i] != '#') return false;
  i = skip_space(i + 1);
  if (i == text.size() || !is_start(text[i])) return false;
  const std::size_t key_begin = i;
  while (i < text.size() && is_part(text[i])) ++i;
  key = text.substr(key_begin, i - key_begin);
  i = skip_space(i);
  if (i == text.size() || text[i] != '=') return false;
  value = text.substr(i + 1);
  return true;
}

// The `# key = value` lines onto `specimen`; returns them as a JSON object (key → value) for the
// comparison with the sidecar.
nlohmann::json read_metadata_lines(const std::vector<CsvLine>& lines, const std::string& path,
                                   SpecimenInfo& specimen) {
  nlohmann::json metadata = nlohmann::json::object();
  for (const auto& line : lines) {
    std::string key, raw_value;
    if (!is_blank_or_comment(line.text) || !parse_metadata_line(line.text, key, raw_value)) continue;
    std::string value_text = trim(raw_value);
    if (value_text.size() >= 2 && value_text.front() == '"' && value_text.back() == '"')
      value_text = value_text.substr(1, value_text.size() - 2);
    const auto error = [&](const std::string& message) {
      return InputError(message, path, line.number, 0, key);
    };
    nlohmann::json value = value_text;
    if (specimen_keys::is_numeric(key))
      value = parse_csv_number(value_text, key, path, line.number, 0);
    if (metadata.contains(key) && metadata[key] != value) throw error("given twice with different values");
    specimen_keys::apply(specimen, key, value, error);
    metadata[key] = value;
  }
  return metadata;
}

// Where the signals sit in a row: time, then load (force or stress) and motion (displacement or
// strain).
struct SignalColumns {
  int time = -1, load = -1, motion = -1;
  bool force_input = false;
};

SignalColumns signal_columns(const std::vector<std::string>& names, const std::string& path,
                             int header_line) {
  static const char* kColumns[] = {"time_s", "force_N", "displacement_mm", "stress_MPa", "strain"};
  int column_of[5] = {-1, -1, -1, -1, -1};
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int column = static_cast<int>(i) + 1;
    if (names[i].rfind("x_", 0) == 0) continue;
    const auto known = std::find_if(std::begin(kColumns), std::end(kColumns),
                                    [&](const char* c) { return names[i] == c; });
    if (known == std::end(kColumns))
      throw InputError("unknown column '" + names[i] +
                           "' (expected time_s and force_N, displacement_mm or stress_MPa, strain)" +
                           unknown_column_hint(names[i]),
                       path, header_line, column);
    int& slot = column_of[known - std::begin(kColumns)];
    if (slot >= 0) throw InputError("duplicate column '" + names[i] + "'", path, header_line, column);
    slot = static_cast<int>(i);
  }
  const bool force_input = column_of[1] >= 0 || column_of[2] >= 0;
  const bool stress_input = column_of[3] >= 0 || column_of[4] >= 0;
  const auto missing = [&](const std::string& what) {
    return InputError("missing required column " + what, path, header_line);
  };
  if (column_of[0] < 0) throw missing("'time_s'");
  if (force_input && stress_input)
    throw InputError("give either force_N, displacement_mm or stress_MPa, strain, not both", path,
                     header_line);
  if (!stress_input && (column_of[1] < 0 || column_of[2] < 0))
    throw missing(column_of[1] < 0 ? "'force_N'" : "'displacement_mm'");
  if (stress_input && (column_of[3] < 0 || column_of[4] < 0))
    throw missing(column_of[3] < 0 ? "'stress_MPa'" : "'strain'");
  return {column_of[0], force_input ? column_of[1] : column_of[3],
          force_input ? column_of[2] : column_of[4], force_input};
}

// The data rows from `next` on: time into `time_s` (strictly increasing), the other two signals
// as they stand in the file.
void read_samples(const std::vector<CsvLine>& lines, std::size_t next,
                  const std::vector<std::string>& names, const SignalColumns& columns,
                  const std::string& path, std::vector<double>& time_s, std::vector<double>& load,
                  std::vector<double>& motion) {
  for (; next < lines.size(); ++next) {
    const CsvLine& line = lines[next];
    if (is_blank_or_comment(line.text)) continue;
    const std::vector<std::string> fields = split_csv_fields(line.text, path, line.number);
    if (fields.size() != names.size())
      throw InputError("row has " + std::to_string(fields.size()) + " fields, header has " +
                           std::to_string(names.size()),
                       path, line.number, static_cast<int>(std::min(fields.size(), names.size())) + 1);
    const auto number = [&](int column) {
      return parse_csv_number(fields[column], names[column], path, line.number, column + 1);
    };
    const double t = number(columns.time);
    if (!time_s.empty() && !(t > time_s.back()))
      throw InputError("time_s is not increasing", path, line.number, columns.time + 1);
    time_s.push_back(t);
    load.push_back(number(columns.load));
    motion.push_back(number(columns.motion));
  }
}

}  // namespace

WaveformRecord read_waveform(const std::string& signals_path, const std::string& sidecar_path) {
  WaveformRecord record;
  record.source_file = signals_path;
  const std::string bytes = core::read_file(signals_path);
  record.source_sha256 = core::sha256_hex(bytes);
  const std::vector<CsvLine> lines = split_csv_lines(bytes, signals_path);
  const nlohmann::json from_lines = read_metadata_lines(lines, signals_path, record.specimen);
  if (!sidecar_path.empty())
    specimen_keys::apply_sidecar(record.specimen, from_lines, sidecar_path, signals_path);

  std::size_t next = 0;
  while (next < lines.size() && is_blank_or_comment(lines[next].text)) ++next;
  if (next == lines.size())
    throw InputError("no header row (empty file)", signals_path, static_cast<int>(lines.size()) + 1);
  const CsvLine& header = lines[next++];
  const std::vector<std::string> names = split_csv_fields(header.text, signals_path, header.number);
  const SignalColumns columns = signal_columns(names, signals_path, header.number);
  std::vector<double> load, motion;
  read_samples(lines, next, names, columns, signals_path, record.time_s, load, motion);
  if (record.time_s.empty()) throw InputError("no data rows after the header", signals_path, header.number);
  if (!record.specimen.has_mode)
    throw InputError("specimen mode is required ('# mode = shear' or the sidecar)", signals_path, 0, 0, "mode");
  if (!columns.force_input) {
    record.stress_MPa = std::move(load);
    record.strain = std::move(motion);
    return record;
  }
  try {
    stress_strain_from_force(record.specimen, load, motion, record.stress_MPa, record.strain);
  } catch (const InputError& e) {
    throw InputError(e.detail(), sidecar_path.empty() ? signals_path : sidecar_path, 0, 0, e.key());
  }
  return record;
}

}  // namespace fitlib::data
