// pyvisco's time-domain CSV (docs/data.md §4).
#include "fitlib/data/relaxation.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/data/csv.hpp"

namespace fitlib::data {
namespace {

struct Columns {
  int time = -1, modulus = -1, temperature = -1, set = -1;
  double to_MPa = 1.0;
  bool kelvin = false;
  core::TestMode mode = core::TestMode::uniaxial;
};

Columns layout(const std::vector<std::string>& names, int name_line, const std::vector<std::string>& units,
               int unit_line, const std::string& file) {
  if (units.size() != names.size())
    throw core::InputError("units row has " + std::to_string(units.size()) + " fields, header has " +
                               std::to_string(names.size()),
                           file, unit_line);
  Columns c;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int column = static_cast<int>(i) + 1;
    const std::string& name = names[i];
    const std::string& unit = units[i];
    const auto claim = [&](int& slot) {
      if (slot >= 0) throw core::InputError("duplicate column '" + name + "'", file, name_line, column);
      slot = static_cast<int>(i);
    };
    if (name == "t") {
      if (unit != "s") throw core::InputError("unit '" + unit + "' of column 't' (expected s)", file, unit_line, column);
      claim(c.time);
    } else if (name == "E_relax" || name == "G_relax") {
      claim(c.modulus);
      c.mode = name[0] == 'G' ? core::TestMode::shear : core::TestMode::uniaxial;
      try {
        c.to_MPa = core::modulus_to_MPa(unit);
      } catch (const core::InputError&) {
        throw core::InputError("unknown unit '" + unit + "' in column '" + name + "' (expected Pa, kPa, MPa or GPa)",
                               file, unit_line, column);
      }
    } else if (name == "T") {
      claim(c.temperature);
      c.kelvin = unit == "K";
      if (!c.kelvin && unit != "C" && unit != "°C" && unit != "degC")
        throw core::InputError("unit '" + unit + "' of column 'T' (expected C or K)", file, unit_line, column);
    } else if (name == "Set") {
      claim(c.set);
    } else {
      throw core::InputError("unknown pyvisco time-domain column '" + name + "' (expected t, E_relax or G_relax, T, Set)" +
                                 unknown_column_hint(name),
                             file, name_line, column);
    }
  }
  if (c.time < 0) throw core::InputError("missing required column 't'", file, name_line);
  if (c.modulus < 0) throw core::InputError("missing required column 'E_relax' (or 'G_relax')", file, name_line);
  return c;
}

}  // namespace

bool looks_like_relaxation_csv(const std::string& bytes) {
  const auto fields = first_content_fields(bytes);
  return !fields.empty() && fields[0] == "t";
}

RelaxationTable parse_relaxation_table(const std::string& bytes, const std::string& file) {
  RelaxationTable table;
  table.source_files.push_back(file);
  table.source_sha256.push_back(core::sha256_hex(bytes));
  const auto lines = split_csv_lines(bytes, file);
  std::size_t next = 0;
  const CsvLine* names = &header_line(lines, next, file);
  const CsvLine* units = next_content_line(lines, next);
  if (!units) throw core::InputError("pyvisco file needs a units row after the header", file, names->number + 1);
  const Columns c = layout(split_csv_fields(names->text, file, names->number), names->number,
                           split_csv_fields(units->text, file, units->number), units->number, file);
  const std::size_t count = std::max({c.time, c.modulus, c.temperature, c.set}) + 1;
  for (const CsvLine* line = next_content_line(lines, next); line; line = next_content_line(lines, next)) {
    const auto f = split_csv_fields(line->text, file, line->number);
    if (f.size() != count)
      throw core::InputError("row has " + std::to_string(f.size()) + " fields, header has " + std::to_string(count),
                             file, line->number, static_cast<int>(std::min(f.size(), count)) + 1);
    RelaxationRow row;
    row.mode = c.mode;
    row.source_file = file;
    row.source_line = line->number;
    row.time_s = parse_csv_number(f[c.time], "time", file, line->number, c.time + 1);
    if (!(row.time_s > 0.0)) throw core::InputError("non-positive time", file, line->number, c.time + 1);
    row.modulus_MPa = parse_csv_number(f[c.modulus], "relaxation modulus", file, line->number, c.modulus + 1) * c.to_MPa;
    if (!(row.modulus_MPa > 0.0))
      throw core::InputError("non-positive relaxation modulus", file, line->number, c.modulus + 1);
    if (c.temperature >= 0) {
      double t = parse_csv_number(f[c.temperature], "temperature", file, line->number, c.temperature + 1);
      if (c.kelvin) t = core::celsius_from_kelvin(t);
      if (!(t > -core::kZeroCelsiusInKelvin))
        throw core::InputError("temperature below absolute zero", file, line->number, c.temperature + 1);
      row.temperature_C = t;
    }
    if (c.set >= 0) row.set = f[c.set];
    table.rows.push_back(row);
  }
  if (table.rows.empty()) throw core::InputError("no data rows after the header", file, units->number);
  return table;
}

RelaxationTable read_relaxation_table(const std::string& path) {
  return parse_relaxation_table(core::read_file(path), path);
}

}  // namespace fitlib::data
