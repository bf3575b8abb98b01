// pyvisco shift-factor files (docs/data.md §3).
#include "fitlib/data/shift_factors.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/data/csv.hpp"

namespace fitlib::data {

ShiftFactorTable parse_shift_factors(const std::string& bytes, const std::string& file_name) {
  ShiftFactorTable table;
  table.source_file = file_name;
  const auto lines = split_csv_lines(bytes, file_name);
  std::size_t next = 0;
  const auto content = [&] { return next_content_line(lines, next); };
  const CsvLine* names = &header_line(lines, next, file_name);
  const auto header = split_csv_fields(names->text, file_name, names->number);
  if (header.size() != 2 || header[0] != "T" || header[1] != "log_aT")
    throw core::InputError("expected the pyvisco shift-factor header 'T,log_aT'", file_name,
                           names->number, 1);
  const CsvLine* units = content();
  if (!units) throw core::InputError("missing units row 'C,-' after the header", file_name,
                                     names->number + 1);
  const auto unit = split_csv_fields(units->text, file_name, units->number);
  if (unit.size() != 2) throw core::InputError("units row needs 2 fields", file_name, units->number);
  const bool kelvin = unit[0] == "K";
  if (!kelvin && unit[0] != "C" && unit[0] != "°C" && unit[0] != "degC")
    throw core::InputError("unit '" + unit[0] + "' of column 'T' (expected C or K)", file_name,
                           units->number, 1);
  for (const CsvLine* line = content(); line; line = content()) {
    const auto f = split_csv_fields(line->text, file_name, line->number);
    if (f.size() != 2)
      throw core::InputError("row has " + std::to_string(f.size()) + " fields, header has 2",
                             file_name, line->number, static_cast<int>(std::min<std::size_t>(f.size(), 2)) + 1);
    ShiftFactor s;
    s.temperature_C = parse_csv_number(f[0], "temperature", file_name, line->number, 1);
    if (kelvin) s.temperature_C = core::celsius_from_kelvin(s.temperature_C);
    if (!(s.temperature_C > -core::kZeroCelsiusInKelvin))
      throw core::InputError("temperature below absolute zero", file_name, line->number, 1);
    s.log10_aT = parse_csv_number(f[1], "log_aT", file_name, line->number, 2);
    for (const auto& other : table.factors)
      if (other.temperature_C == s.temperature_C)
        throw core::InputError("temperature listed twice", file_name, line->number, 1);
    if (s.log10_aT == 0.0) table.reference_C = s.temperature_C;
    table.factors.push_back(s);
  }
  if (table.factors.empty())
    throw core::InputError("no shift factors after the header", file_name, units->number);
  return table;
}

ShiftFactorTable read_shift_factors(const std::string& path) {
  return parse_shift_factors(core::read_file(path), path);
}

std::string format_shift_factors(const ShiftFactorTable& table) {
  std::string s = "T,log_aT\nC,-\n";
  for (const auto& f : table.factors)
    s += format_exact(f.temperature_C) + "," + format_exact(f.log10_aT) + "\n";
  return s;
}

double interpolate_log10_aT(const ShiftFactorTable& table, double temperature_C, double tolerance_C) {
  // An empty table read front() of nothing (a segmentation fault from Python).
  if (table.factors.empty()) throw core::InputError("no shift factors to interpolate", table.source_file);
  if (!std::isfinite(temperature_C) || !(tolerance_C >= 0.0))
    throw core::UsageError("shift factors: temperature and tolerance must be finite (tolerance >= 0), got " +
                           format_exact(temperature_C) + " and " + format_exact(tolerance_C) + " degC");
  std::vector<ShiftFactor> sorted = table.factors;
  std::sort(sorted.begin(), sorted.end(),
            [](const ShiftFactor& a, const ShiftFactor& b) { return a.temperature_C < b.temperature_C; });
  const double lo = sorted.front().temperature_C, hi = sorted.back().temperature_C;
  if (temperature_C < lo - tolerance_C || temperature_C > hi + tolerance_C)
    throw core::InputError("temperature " + format_exact(temperature_C) + " degC is outside the shift factors (" +
                               format_exact(lo) + " … " + format_exact(hi) + " degC)",
                           table.source_file);
  if (sorted.size() == 1 || temperature_C <= lo) return sorted.front().log10_aT;
  if (temperature_C >= hi) return sorted.back().log10_aT;
  std::size_t k = 1;
  while (sorted[k].temperature_C < temperature_C) ++k;
  const auto& a = sorted[k - 1];
  const auto& b = sorted[k];
  const double w = (temperature_C - a.temperature_C) / (b.temperature_C - a.temperature_C);
  return a.log10_aT + w * (b.log10_aT - a.log10_aT);
}

}  // namespace fitlib::data
