// Dynamic-test tables (docs/formats.md §1): native CSV and pyvisco's two-row-header CSV.
#include "fitlib/data/table.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/data/csv.hpp"

namespace fitlib::data {
namespace {

// A time column in a dynamic-test table: the user has relaxation data, which the pyvisco layout
// reads (docs/data.md §4), not the native table.
std::string time_domain_hint(const std::string& column) {
  std::string lower;
  for (char c : column) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool time_like = lower == "t" || lower.rfind("time", 0) == 0 || lower.find("relax") != std::string::npos;
  if (!time_like) return "";
  return "; relaxation data (a modulus over time) are read in pyvisco's layout: a header t,E_relax (or G_relax), "
         "a units row s,MPa, then the rows, with --format pyvisco (docs/data.md §4)";
}
// A pyvisco frequency table read as native: "unknown column 'f'" said nothing of --format.
std::string pyvisco_hint(const std::string& column) {
  for (const char* name : {"f", "omega", "E_stor", "E_loss", "G_stor", "G_loss", "Set"})
    if (column == name)
      return "; did you mean --format pyvisco? '" + column +
             "' is a column of pyvisco's layout (f, E_stor, E_loss, T, Set, a units row; docs/data.md)";
  return "";
}
constexpr double kMaxTableMagnitude = 1e100;   // any number in a table
constexpr double kMinTableFrequency_Hz = 1e-100;

enum Role {
  kMode, kFrequencyHz, kAngularFrequency, kStorage, kLoss, kAbsModulus, kTanDelta, kLossAngleDeg,
  kTemperatureC, kTemperatureK, kStrainAmplitude, kMeanStrain, kMeanModulus, kOrientation,
  kMaterial, kSpecimen, kSet, kWeight, kRoleCount
};

// Alternatives for one quantity share a slot, so giving both is a duplicate.
int slot_of(Role role) {
  switch (role) {
    case kAngularFrequency: return kFrequencyHz;
    case kTemperatureK: return kTemperatureC;
    case kLossAngleDeg: return kTanDelta;
    default: return role;
  }
}

struct NamedRole {
  const char* name;
  Role role;
};
constexpr NamedRole kExactNames[] = {
    {"mode", kMode},
    {"frequency_Hz", kFrequencyHz},
    {"angular_frequency_rad_s", kAngularFrequency},
    {"tan_delta", kTanDelta},
    {"loss_angle_deg", kLossAngleDeg},
    {"temperature_C", kTemperatureC},
    {"temperature_K", kTemperatureK},
    {"strain_amplitude", kStrainAmplitude},
    {"mean_strain", kMeanStrain},
    {"orientation", kOrientation},
    {"material", kMaterial},
    {"specimen", kSpecimen},
    {"set", kSet},
    {"weight", kWeight},
};
// Modulus columns carry their unit as a suffix: storage_MPa, loss_kPa, ...
constexpr NamedRole kModulusPrefixes[] = {
    {"storage_", kStorage},
    {"loss_", kLoss},
    {"abs_modulus_", kAbsModulus},
    {"mean_modulus_", kMeanModulus},
};
constexpr const char* kKnownColumns =
    "mode, frequency_Hz, angular_frequency_rad_s, storage_<U>, loss_<U>, abs_modulus_<U>, "
    "tan_delta, loss_angle_deg, temperature_C, temperature_K, strain_amplitude, mean_strain, "
    "mean_modulus_<U>, orientation, material, specimen, set, weight (U: Pa, kPa, MPa, GPa; "
    "x_... for notes)";

// Where each quantity sits in a row (0-based field index, -1 = absent) and its unit factor.
struct Layout {
  std::array<int, kRoleCount> column;
  std::array<double, kRoleCount> to_MPa;
  std::size_t field_count = 0;
  int header_line = 0;  // last header line (pyvisco: the units row)
  bool has_default_mode = false;
  core::TestMode default_mode = core::TestMode::shear;
  Layout() {
    column.fill(-1);
    to_MPa.fill(1.0);
  }
  bool has(Role role) const { return column[role] >= 0; }
};

// One data row's fields under a layout, with the row's error and number helpers.
struct RowFields {
  const std::vector<std::string>& fields;
  const Layout& layout;
  const std::string& file;
  int line;

  const std::string& text(Role role) const { return fields[layout.column[role]]; }
  core::InputError fail(Role role, const std::string& message) const {
    return core::InputError(message, file, line, layout.column[role] + 1);
  }
  // Range contract (docs/decisions.md "Table value range"): beyond it ω, 1/ω or the moduli
  // overflow in the fit.
  double number(Role role, const char* what) const {
    const double v = parse_csv_number(text(role), what, file, line, layout.column[role] + 1);
    if (std::abs(v) > kMaxTableMagnitude) throw fail(role, std::string(what) + " beyond +-1e100");
    return v;
  }
  // Optional columns: an empty cell means "not given".
  bool given(Role role) const { return layout.has(role) && !text(role).empty(); }
};

void read_mode(const RowFields& in, core::TestCondition& c) {
  if (in.given(kMode)) {
    const auto mode = core::test_mode_from_label(in.text(kMode));
    if (!mode)
      throw in.fail(kMode, "unknown test mode '" + in.text(kMode) + "' (expected " + kModeLabels + ")");
    c.mode = *mode;
  } else if (in.layout.has_default_mode) {
    c.mode = in.layout.default_mode;
  } else {
    throw in.fail(kMode, "empty mode");
  }
}

void read_frequency(const RowFields& in, core::TestCondition& c) {
  if (in.layout.has(kFrequencyHz)) {
    c.frequency_Hz = in.number(kFrequencyHz, "frequency");
    if (!(c.frequency_Hz > 0.0)) throw in.fail(kFrequencyHz, "non-positive frequency");
    if (c.frequency_Hz < kMinTableFrequency_Hz) throw in.fail(kFrequencyHz, "frequency below 1e-100 Hz");
  } else {
    const double omega = in.number(kAngularFrequency, "angular frequency");
    if (!(omega > 0.0)) throw in.fail(kAngularFrequency, "non-positive angular frequency");
    if (omega < kMinTableFrequency_Hz) throw in.fail(kAngularFrequency, "angular frequency below 1e-100 rad/s");
    c.frequency_Hz = omega / (2.0 * core::kPi);
  }
}

// E′, E″ from storage and loss columns, or from |E*| with tan δ or δ.
void read_moduli(const RowFields& in, DynamicTestRow& row) {
  const auto& to_MPa = in.layout.to_MPa;
  if (in.layout.has(kStorage)) {
    row.storage_MPa = in.number(kStorage, "storage modulus") * to_MPa[kStorage];
    if (!(row.storage_MPa > 0.0)) throw in.fail(kStorage, "non-positive storage modulus");
    row.loss_MPa = in.number(kLoss, "loss modulus") * to_MPa[kLoss];
    if (row.loss_MPa < 0.0) throw in.fail(kLoss, "negative loss modulus");
    return;
  }
  const double abs_MPa = in.number(kAbsModulus, "modulus") * to_MPa[kAbsModulus];
  if (!(abs_MPa > 0.0)) throw in.fail(kAbsModulus, "non-positive modulus");
  if (in.layout.has(kTanDelta)) {
    const double tan_delta = in.number(kTanDelta, "tan delta");
    if (tan_delta < 0.0) throw in.fail(kTanDelta, "negative tan delta");
    row.storage_MPa = abs_MPa / std::sqrt(1.0 + tan_delta * tan_delta);
    row.loss_MPa = row.storage_MPa * tan_delta;
  } else {
    const double delta_deg = in.number(kLossAngleDeg, "loss angle");
    if (delta_deg < 0.0 || delta_deg >= 90.0)
      throw in.fail(kLossAngleDeg, "loss angle outside [0, 90) degrees");
    const double delta = delta_deg * core::kPi / 180.0;
    row.storage_MPa = abs_MPa * std::cos(delta);
    row.loss_MPa = abs_MPa * std::sin(delta);
  }
}

void read_temperature(const RowFields& in, core::TestCondition& c) {
  if (in.given(kTemperatureC)) {
    c.temperature_C = in.number(kTemperatureC, "temperature");
    if (!(c.temperature_C > -core::kZeroCelsiusInKelvin))
      throw in.fail(kTemperatureC, "temperature below absolute zero");
  } else if (in.given(kTemperatureK)) {
    const double t_K = in.number(kTemperatureK, "temperature");
    if (!(t_K > 0.0)) throw in.fail(kTemperatureK, "temperature below absolute zero");
    c.temperature_C = core::celsius_from_kelvin(t_K);
  }
}

// Amplitude, mean strain and modulus, orientation, weight and labels.
void read_optional(const RowFields& in, DynamicTestRow& row) {
  core::TestCondition& c = row.condition;
  if (in.given(kStrainAmplitude)) {
    c.strain_amplitude = in.number(kStrainAmplitude, "strain amplitude");
    if (c.strain_amplitude < 0.0) throw in.fail(kStrainAmplitude, "negative strain amplitude");
  }
  if (in.given(kMeanStrain)) c.mean_strain = in.number(kMeanStrain, "mean strain");
  if (in.given(kMeanModulus)) {
    row.mean_modulus_MPa = in.number(kMeanModulus, "mean modulus") * in.layout.to_MPa[kMeanModulus];
    row.has_mean_modulus = true;
  }
  if (in.given(kOrientation)) {
    c.orientation = in.text(kOrientation);
    if (!is_known_orientation(c.orientation))
      throw in.fail(kOrientation, "unknown orientation '" + c.orientation + "' (expected " +
                                      kOrientationLabels + ")");
  }
  if (in.given(kWeight)) {
    row.weight = in.number(kWeight, "weight");
    if (row.weight < 0.0) throw in.fail(kWeight, "negative weight");
  }
  if (in.layout.has(kMaterial)) row.material = in.text(kMaterial);
  if (in.layout.has(kSpecimen)) row.specimen = in.text(kSpecimen);
  if (in.layout.has(kSet)) row.set = in.text(kSet);
}

class TableParser {
 public:
  TableParser(std::string file, const ReadOptions& options, DynamicTestTable& table)
      : file_(std::move(file)), options_(options), table_(table) {}

  void parse(const std::vector<CsvLine>& lines) {
    std::size_t next = 0;
    const CsvLine* header = next_content_line(lines, next);
    if (!header)
      throw core::InputError("no header row (empty file)", file_,
                             static_cast<int>(lines.size()) + 1);
    const std::vector<std::string> names = split_csv_fields(header->text, file_, header->number);
    if (options_.format == TableFormat::pyvisco) {
      const CsvLine* units = next_content_line(lines, next);
      if (!units)
        throw core::InputError("pyvisco file needs a units row after the header", file_,
                               header->number + 1);
      layout_pyvisco(names, header->number, split_csv_fields(units->text, file_, units->number),
                     units->number);
    } else {
      layout_native(names, header->number);
    }
    read_rows(lines, next);
  }

 private:
  const CsvLine* next_content_line(const std::vector<CsvLine>& lines, std::size_t& next) const {
    while (next < lines.size() && is_blank_or_comment(lines[next].text)) ++next;
    return next < lines.size() ? &lines[next++] : nullptr;
  }

  void assign(Role role, std::size_t index, const std::vector<std::string>& names, int line) {
    for (int r = 0; r < kRoleCount; ++r) {
      const int other = layout_.column[r];
      if (other >= 0 && slot_of(static_cast<Role>(r)) == slot_of(role))
        throw core::InputError("duplicate column '" + names[index] + "' (same quantity as column " +
                                   std::to_string(other + 1) + " '" + names[other] + "')",
                               file_, line, static_cast<int>(index) + 1);
    }
    layout_.column[role] = static_cast<int>(index);
  }

  void set_modulus_unit(Role role, const std::string& unit, const std::string& name, int line,
                        std::size_t index) {
    try {
      layout_.to_MPa[role] = core::modulus_to_MPa(unit);
    } catch (const core::InputError&) {
      throw core::InputError("unknown unit '" + unit + "' in column '" + name +
                                 "' (expected Pa, kPa, MPa or GPa)",
                             file_, line, static_cast<int>(index) + 1);
    }
  }

  void layout_native(const std::vector<std::string>& names, int line) {
    layout_.field_count = names.size();
    layout_.header_line = line;
    layout_.has_default_mode = options_.has_default_mode;
    layout_.default_mode = options_.default_mode;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string& name = names[i];
      const int column = static_cast<int>(i) + 1;
      if (name.empty()) throw core::InputError("empty column name", file_, line, column);
      if (name.rfind("x_", 0) == 0) continue;
      bool known = false;
      for (const auto& exact : kExactNames)
        if (name == exact.name) {
          assign(exact.role, i, names, line);
          known = true;
        }
      if (!known)
        for (const auto& prefix : kModulusPrefixes) {
          const std::string p = prefix.name;
          if (name.size() > p.size() && name.compare(0, p.size(), p) == 0) {
            set_modulus_unit(prefix.role, name.substr(p.size()), name, line, i);
            assign(prefix.role, i, names, line);
            known = true;
            break;
          }
        }
      if (known) continue;
      const std::string message = "unknown column '" + name + "' (known: " + kKnownColumns + ")" +
                                  unknown_column_hint(name) + time_domain_hint(name) + pyvisco_hint(name);
      if (!options_.allow_unknown_columns) throw core::InputError(message, file_, line, column);
      table_.warnings.push_back(core::InputError(message + "; ignored", file_, line, column).what());
    }
    check_required_native(line);
  }

  void check_required_native(int line) const {
    const auto missing = [&](const std::string& what) {
      return core::InputError("missing required column " + what, file_, line);
    };
    if (!layout_.has(kMode) && !layout_.has_default_mode)
      throw missing("'mode' (or give a default mode, fitcli --mode)");
    if (!layout_.has(kFrequencyHz) && !layout_.has(kAngularFrequency))
      throw missing("'frequency_Hz' (or 'angular_frequency_rad_s')");
    const bool storage_loss = layout_.has(kStorage) || layout_.has(kLoss);
    const bool polar = layout_.has(kAbsModulus) || layout_.has(kTanDelta) ||
                       layout_.has(kLossAngleDeg);
    if (storage_loss && polar) {
      const Role extra = layout_.has(kAbsModulus) ? kAbsModulus
                         : layout_.has(kTanDelta) ? kTanDelta
                                                  : kLossAngleDeg;
      throw core::InputError(
          "give either storage_<U> and loss_<U> or abs_modulus_<U> with tan_delta or "
          "loss_angle_deg, not both",
          file_, line, layout_.column[extra] + 1);
    }
    if (storage_loss || !polar) {
      if (!layout_.has(kStorage)) throw missing("'storage_<U>' (U: Pa, kPa, MPa, GPa)");
      if (!layout_.has(kLoss)) throw missing("'loss_<U>' (U: Pa, kPa, MPa, GPa)");
    } else {
      if (!layout_.has(kAbsModulus)) throw missing("'abs_modulus_<U>' (U: Pa, kPa, MPa, GPa)");
      if (!layout_.has(kTanDelta) && !layout_.has(kLossAngleDeg))
        throw missing("'tan_delta' or 'loss_angle_deg' (with abs_modulus_<U>)");
    }
  }

  // pyvisco: `f, E_stor, E_loss[, T, Set]` (or G_...) and a units row `Hz, MPa, MPa, C, -`.
  void layout_pyvisco(const std::vector<std::string>& names, int name_line,
                      const std::vector<std::string>& units, int unit_line) {
    if (units.size() != names.size())
      throw core::InputError("units row has " + std::to_string(units.size()) +
                                 " fields, header has " + std::to_string(names.size()),
                             file_, unit_line, static_cast<int>(std::min(units.size(), names.size())) + 1);
    layout_.field_count = names.size();
    layout_.header_line = unit_line;
    char modulus_letter = 0;
    for (std::size_t i = 0; i < names.size(); ++i) {
      const std::string& name = names[i];
      const std::string& unit = units[i];
      const int column = static_cast<int>(i) + 1;
      const auto bad_unit = [&](const std::string& expected) {
        return core::InputError("unit '" + unit + "' of column '" + name + "' (expected " +
                                    expected + ")",
                                file_, unit_line, column);
      };
      if (name == "f") {
        if (unit != "Hz") throw bad_unit("Hz");
        assign(kFrequencyHz, i, names, name_line);
      } else if (name == "E_stor" || name == "E_loss" || name == "G_stor" || name == "G_loss") {
        if (modulus_letter && modulus_letter != name[0])
          throw core::InputError("mixes E and G moduli", file_, name_line, column);
        modulus_letter = name[0];
        const Role role = name.substr(2) == "stor" ? kStorage : kLoss;
        set_modulus_unit(role, unit, name, unit_line, i);
        assign(role, i, names, name_line);
      } else if (name == "T") {
        if (unit == "C" || unit == "°C" || unit == "degC")
          assign(kTemperatureC, i, names, name_line);
        else if (unit == "K")
          assign(kTemperatureK, i, names, name_line);
        else
          throw bad_unit("C or K");
      } else if (name == "Set") {
        assign(kSet, i, names, name_line);
      } else if (name == "t" || name == "E_relax") {
        throw core::InputError("time-domain pyvisco data (t, E_relax) is not a dynamic-test table",
                               file_, name_line, column);
      } else {
        throw core::InputError("unknown pyvisco column '" + name +
                                   "' (expected f, E_stor, E_loss or G_stor, G_loss, T, Set)",
                               file_, name_line, column);
      }
    }
    if (!layout_.has(kFrequencyHz))
      throw core::InputError("missing required pyvisco column 'f'", file_, name_line);
    if (!layout_.has(kStorage))
      throw core::InputError("missing required pyvisco column 'E_stor' (or 'G_stor')", file_,
                             name_line);
    if (!layout_.has(kLoss))
      throw core::InputError("missing required pyvisco column 'E_loss' (or 'G_loss')", file_,
                             name_line);
    // The column letter decides the mode: E is tensile (uniaxial), G is shear.
    layout_.has_default_mode = true;
    layout_.default_mode = modulus_letter == 'G' ? core::TestMode::shear
                                                 : core::TestMode::uniaxial;
  }

  void read_rows(const std::vector<CsvLine>& lines, std::size_t next) {
    int skipped = 0;
    for (; next < lines.size(); ++next) {
      const CsvLine& line = lines[next];
      if (is_blank_or_comment(line.text)) continue;
      try {
        table_.rows.push_back(parse_row(line));
      } catch (const core::InputError& e) {
        if (!options_.skip_bad_rows) throw;
        table_.warnings.push_back(std::string("skipped row: ") + e.what());
        ++skipped;
      }
    }
    if (!table_.rows.empty() &&
        std::all_of(table_.rows.begin(), table_.rows.end(), [](const DynamicTestRow& r) { return r.weight == 0.0; }))
      throw core::InputError("every row has weight 0: nothing to fit", file_, layout_.header_line, 0, "weight");
    if (table_.rows.empty()) {
      if (skipped > 0)
        throw core::InputError("no valid data rows (" + std::to_string(skipped) + " skipped)",
                               file_, layout_.header_line);
      throw core::InputError("no data rows after the header", file_, layout_.header_line);
    }
  }

  DynamicTestRow parse_row(const CsvLine& line) const {
    const std::vector<std::string> fields = split_csv_fields(line.text, file_, line.number);
    if (fields.size() != layout_.field_count)
      throw core::InputError("row has " + std::to_string(fields.size()) + " fields, header has " +
                                 std::to_string(layout_.field_count),
                             file_, line.number,
                             static_cast<int>(std::min(fields.size(), layout_.field_count)) + 1);
    const RowFields in{fields, layout_, file_, line.number};
    DynamicTestRow row;
    row.source_file = file_;
    row.source_line = line.number;
    read_mode(in, row.condition);
    read_frequency(in, row.condition);
    read_moduli(in, row);
    read_temperature(in, row.condition);
    read_optional(in, row);
    return row;
  }

  std::string file_;
  const ReadOptions& options_;
  DynamicTestTable& table_;
  Layout layout_;
};

}  // namespace

DynamicTestTable parse_dynamic_table(const std::string& bytes, const std::string& file_name,
                                     const ReadOptions& options) {
  DynamicTestTable table;
  table.source_files.push_back(file_name);
  table.source_sha256.push_back(core::sha256_hex(bytes));
  TableParser(file_name, options, table).parse(split_csv_lines(bytes, file_name));
  return table;
}

DynamicTestTable read_dynamic_table(const std::string& path, const ReadOptions& options) {
  return parse_dynamic_table(core::read_file(path), path, options);
}

DynamicTestTable read_dynamic_tables(const std::vector<std::string>& paths,
                                     const ReadOptions& options) {
  DynamicTestTable all;
  for (const auto& path : paths) {
    DynamicTestTable one = read_dynamic_table(path, options);
    all.rows.insert(all.rows.end(), one.rows.begin(), one.rows.end());
    all.source_files.insert(all.source_files.end(), one.source_files.begin(),
                            one.source_files.end());
    all.source_sha256.insert(all.source_sha256.end(), one.source_sha256.begin(),
                             one.source_sha256.end());
    all.warnings.insert(all.warnings.end(), one.warnings.begin(), one.warnings.end());
  }
  return all;
}

std::string format_dynamic_table(const DynamicTestTable& table) {
  std::ostringstream out;
  out << "# fitlib dynamic-test table (formats.md section 1); moduli in MPa\n"
      << "mode,orientation,frequency_Hz,temperature_C,strain_amplitude,mean_strain,storage_MPa,"
         "loss_MPa,mean_modulus_MPa,weight,material,specimen,set\n";
  for (const auto& row : table.rows) {
    const auto& c = row.condition;
    const std::string at = " of a table row at " + core::short_number(c.frequency_Hz) + " Hz";
    for (const auto& [what, value] : {std::pair<const char*, double>{"frequency", c.frequency_Hz},
                                      {"storage modulus", row.storage_MPa}, {"loss modulus", row.loss_MPa},
                                      {"strain amplitude", c.strain_amplitude}, {"mean strain", c.mean_strain}})
      core::require_finite(value, what + at);
    out << core::to_string(c.mode) << ',' << c.orientation << ',' << format_exact(c.frequency_Hz)
        << ',' << (c.has_temperature() ? format_exact(c.temperature_C) : "") << ','
        << format_exact(c.strain_amplitude) << ',' << format_exact(c.mean_strain) << ','
        << format_exact(row.storage_MPa) << ',' << format_exact(row.loss_MPa) << ','
        << (row.has_mean_modulus ? format_exact(row.mean_modulus_MPa) : "") << ','
        << format_exact(row.weight) << ',' << quote_csv_field(row.material) << ','
        << quote_csv_field(row.specimen) << ',' << quote_csv_field(row.set) << '\n';
  }
  return out.str();
}

void write_dynamic_table(const std::string& path, const DynamicTestTable& table) {
  core::write_file_atomically(path, format_dynamic_table(table));
}

}  // namespace fitlib::data
