// Quasi-static test tables (docs/formats.md §"Quasi-static tests").
#include "fitlib/data/quasi_static.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/csv.hpp"

namespace fitlib::data {
namespace {

using core::DeformationMode;

// Column indices (−1: absent). `stretch` holds the stretch column or its strain alternative,
// read as λ = 1 + stretch_scale · value + stretch_offset.
struct Columns {
  int mode = -1, stretch = -1, shear_strain = -1, volume_ratio = -1, nominal_stress = -1, pressure = -1;
  int specimen = -1, temperature = -1, strain_rate = -1;
  double stretch_scale = 1.0, stretch_offset = 0.0;
  std::string stretch_name = "stretch";
  int count = 0;
};

constexpr const char* kKnownColumns =
    "mode, stretch (or strain, strain_percent), shear_strain, volume_ratio, nominal_stress_MPa, pressure_MPa, "
    "specimen, temperature_C, strain_rate_per_s";

bool is_abscissa_column(const std::string& name) {
  return name == "stretch" || name == "strain" || name == "strain_percent" || name == "shear_strain" ||
         name == "volume_ratio";
}

Columns layout(const std::vector<std::string>& names, int line, const std::string& file) {
  Columns c;
  c.count = static_cast<int>(names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    const int column = static_cast<int>(i) + 1;
    const auto claim = [&](int& slot) {
      if (slot >= 0) throw core::InputError("duplicate column '" + name + "'", file, line, column);
      slot = static_cast<int>(i);
    };
    if (name == "mode") claim(c.mode);
    else if (name == "stretch" || name == "strain" || name == "strain_percent") {
      if (c.stretch >= 0)
        throw core::InputError("column '" + name + "' repeats the stretch given by '" + c.stretch_name +
                                   "' (one of stretch, strain, strain_percent)",
                               file, line, column);
      claim(c.stretch);
      c.stretch_name = name;
      c.stretch_offset = name == "stretch" ? 0.0 : 1.0;
      c.stretch_scale = name == "strain_percent" ? 0.01 : 1.0;
    } else if (name == "shear_strain") claim(c.shear_strain);
    else if (name == "volume_ratio") claim(c.volume_ratio);
    else if (name == "nominal_stress_MPa") claim(c.nominal_stress);
    else if (name == "pressure_MPa") claim(c.pressure);
    else if (name == "specimen") claim(c.specimen);
    else if (name == "temperature_C") claim(c.temperature);
    else if (name == "strain_rate_per_s") claim(c.strain_rate);
    else
      throw core::InputError("unknown quasi-static column '" + name + "' (known: " + kKnownColumns + ")" +
                                 unknown_column_hint(name),
                             file, line, column);
  }
  if (c.mode < 0) throw core::InputError("missing required column 'mode'", file, line);
  if (c.stretch < 0 && c.shear_strain < 0 && c.volume_ratio < 0)
    throw core::InputError("missing an abscissa column (stretch, strain, strain_percent, shear_strain or volume_ratio)",
                           file, line);
  if (c.nominal_stress < 0 && c.pressure < 0)
    throw core::InputError("missing a stress column (nominal_stress_MPa or pressure_MPa)", file, line);
  return c;
}

// The field a mode needs: present in the header and non-empty.
double required(const std::vector<std::string>& f, int index, const std::string& name, DeformationMode mode,
                const std::string& file, int line) {
  if (index < 0)
    throw core::InputError(std::string("a ") + core::to_string(mode) + " row needs the column '" + name +
                               "', which the header lacks",
                           file, line);
  if (f[index].empty())
    throw core::InputError(std::string("empty '") + name + "' in a " + core::to_string(mode) + " row", file, line,
                           index + 1);
  return parse_csv_number(f[index], name, file, line, index + 1);
}

// Columns of other modes stay empty: a value there is a mislabelled row.
void require_empty(const std::vector<std::string>& f, std::initializer_list<std::pair<int, const char*>> columns,
                   DeformationMode mode, const std::string& file, int line) {
  for (const auto& [index, name] : columns)
    if (index >= 0 && !f[index].empty())
      throw core::InputError(std::string("a ") + core::to_string(mode) + " row has a value in '" + name +
                                 "' (leave the other modes' columns empty)",
                             file, line, index + 1);
}

QuasiStaticRow parse_row(const std::vector<std::string>& f, const Columns& c, const std::string& file, int line) {
  QuasiStaticRow row;
  row.source_file = file;
  row.source_line = line;
  const auto mode = core::deformation_mode_from_label(f[c.mode]);
  if (!mode)
    throw core::InputError("unknown mode '" + f[c.mode] + "' (expected " + core::kDeformationModeLabels + ")", file,
                           line, c.mode + 1);
  row.mode = *mode;
  switch (row.mode) {
    case DeformationMode::simple_shear:
      row.abscissa = required(f, c.shear_strain, "shear_strain", row.mode, file, line);
      row.stress_MPa = required(f, c.nominal_stress, "nominal_stress_MPa", row.mode, file, line);
      require_empty(f, {{c.stretch, "stretch"}, {c.volume_ratio, "volume_ratio"}, {c.pressure, "pressure_MPa"}},
                    row.mode, file, line);
      break;
    case DeformationMode::volumetric:
      row.abscissa = required(f, c.volume_ratio, "volume_ratio", row.mode, file, line);
      if (!(row.abscissa > 0.0)) throw core::InputError("volume ratio must be > 0", file, line, c.volume_ratio + 1);
      row.stress_MPa = required(f, c.pressure, "pressure_MPa", row.mode, file, line);
      require_empty(f, {{c.stretch, "stretch"}, {c.shear_strain, "shear_strain"}, {c.nominal_stress, "nominal_stress_MPa"}},
                    row.mode, file, line);
      break;
    default:
      row.abscissa = c.stretch_offset + c.stretch_scale * required(f, c.stretch, c.stretch_name, row.mode, file, line);
      if (!(row.abscissa > 0.0))
        throw core::InputError("stretch must be > 0 (" + c.stretch_name + " gives " + format_exact(row.abscissa) + ")",
                               file, line, c.stretch + 1);
      row.stress_MPa = required(f, c.nominal_stress, "nominal_stress_MPa", row.mode, file, line);
      require_empty(f, {{c.shear_strain, "shear_strain"}, {c.volume_ratio, "volume_ratio"}, {c.pressure, "pressure_MPa"}},
                    row.mode, file, line);
  }
  if (c.specimen >= 0) row.specimen = f[c.specimen];
  if (c.temperature >= 0 && !f[c.temperature].empty())
    row.temperature_C = parse_csv_number(f[c.temperature], "temperature", file, line, c.temperature + 1);
  if (c.strain_rate >= 0 && !f[c.strain_rate].empty()) {
    row.strain_rate_per_s = parse_csv_number(f[c.strain_rate], "strain rate", file, line, c.strain_rate + 1);
    if (!(row.strain_rate_per_s >= 0.0))
      throw core::InputError("negative strain rate", file, line, c.strain_rate + 1);
  }
  return row;
}

}  // namespace

bool looks_like_quasi_static_csv(const std::string& bytes) {
  const auto fields = first_content_fields(bytes);
  return std::find(fields.begin(), fields.end(), "mode") != fields.end() &&
         std::any_of(fields.begin(), fields.end(), is_abscissa_column);
}

QuasiStaticTable parse_quasi_static_table(const std::string& bytes, const std::string& file) {
  QuasiStaticTable table;
  table.source_files.push_back(file);
  table.source_sha256.push_back(core::sha256_hex(bytes));
  const auto lines = split_csv_lines(bytes, file);
  std::size_t next = 0;
  const CsvLine& header = header_line(lines, next, file);
  const Columns c = layout(split_csv_fields(header.text, file, header.number), header.number, file);
  for (const CsvLine* line = next_content_line(lines, next); line; line = next_content_line(lines, next)) {
    const auto f = split_csv_fields(line->text, file, line->number);
    if (static_cast<int>(f.size()) != c.count)
      throw core::InputError("row has " + std::to_string(f.size()) + " fields, header has " + std::to_string(c.count),
                             file, line->number, std::min(static_cast<int>(f.size()), c.count) + 1);
    table.rows.push_back(parse_row(f, c, file, line->number));
  }
  if (table.rows.empty()) throw core::InputError("no data rows after the header", file, header.number);
  return table;
}

QuasiStaticTable read_quasi_static_table(const std::string& path) {
  return parse_quasi_static_table(core::read_file(path), path);
}

QuasiStaticTable merge_quasi_static_tables(const std::vector<QuasiStaticTable>& tables) {
  QuasiStaticTable all;
  for (const auto& t : tables) {
    all.rows.insert(all.rows.end(), t.rows.begin(), t.rows.end());
    all.source_files.insert(all.source_files.end(), t.source_files.begin(), t.source_files.end());
    all.source_sha256.insert(all.source_sha256.end(), t.source_sha256.begin(), t.source_sha256.end());
  }
  return all;
}

}  // namespace fitlib::data
