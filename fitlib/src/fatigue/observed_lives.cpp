// Reader of the observed-lives CSV (life_fit.hpp).
#include <algorithm>
#include <map>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/csv.hpp"
#include "fitlib/fatigue/life_fit.hpp"

namespace fitlib::fatigue {

namespace {

const std::vector<std::string> kColumns = {"case", "failure_mode", "temperature_C",
                                           "observed_cycles", "observed_h", "cycles_per_h",
                                           "point", "peaks_MPa", "stress_fidelity", "runout"};

Mode parse_mode(const std::string& text, const std::string& file, int line, int column) {
  if (const std::optional<Mode> m = mode_from_string(text)) return *m;
  throw core::InputError("failure_mode '" + text + "' is not radial_crack or separation", file,
                         line, column, "failure_mode");
}

std::vector<double> parse_peaks(const std::string& text, const std::string& file, int line,
                                int column) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ';')) {
    const double v = data::parse_csv_number(item, "peaks_MPa", file, line, column);
    if (!(v > 0.0))
      throw core::InputError("peak stresses must be positive", file, line, column, "peaks_MPa");
    out.push_back(v);
  }
  if (out.empty()) throw core::InputError("no peaks", file, line, column, "peaks_MPa");
  return out;
}

using Columns = std::map<std::string, int>;  // column name → 0-based index

// The header: known, unique names, with the required ones and one way to give the life.
Columns header_columns(const std::vector<std::string>& f, const std::string& file, int line) {
  Columns col;
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (std::find(kColumns.begin(), kColumns.end(), f[k]) == kColumns.end())
      throw core::InputError("unknown column '" + f[k] + "'" + data::unknown_column_hint(f[k]), file, line, int(k) + 1, f[k]);
    if (col.count(f[k]))
      throw core::InputError("duplicate column '" + f[k] + "'", file, line, int(k) + 1, f[k]);
    col[f[k]] = int(k);
  }
  for (const char* need : {"case", "failure_mode", "temperature_C", "peaks_MPa"})
    if (!col.count(need))
      throw core::InputError(std::string("missing column '") + need + "'", file, line, 0, need);
  const bool by_cycles = col.count("observed_cycles") > 0;
  const bool by_hours = col.count("observed_h") && col.count("cycles_per_h");
  if (by_cycles == by_hours)
    throw core::InputError("give observed_cycles, or observed_h with cycles_per_h", file, line, 0,
                           "observed_cycles");
  return col;
}

// One data row: a case with its mode, temperature, life and one point's peaks.
ObservedLife read_life_row(const std::vector<std::string>& f, const Columns& col,
                           const std::string& file, int line) {
  if (f.size() != col.size())
    throw core::InputError("expected " + std::to_string(col.size()) + " fields, found " +
                               std::to_string(f.size()), file, line, int(f.size()) + 1);
  auto field = [&](const std::string& c) { return f[col.at(c)]; };
  auto number = [&](const std::string& c) {
    const double v = data::parse_csv_number(field(c), c, file, line, col.at(c) + 1);
    if (c != "temperature_C" && !(v > 0.0))
      throw core::InputError(c + " must be positive", file, line, col.at(c) + 1, c);
    if (c == "temperature_C" && !(v >= -273.15 && v <= 1000.0))  // as every scene's temperature
      throw core::InputError("temperature_C must be in [-273.15, 1000] degC, got " + field(c), file, line,
                             col.at(c) + 1, c);
    return v;
  };
  ObservedLife row;
  row.name = field("case");
  row.line = line;
  row.mode = parse_mode(field("failure_mode"), file, line, col.at("failure_mode") + 1);
  row.temperature_C = number("temperature_C");
  row.observed_cycles = col.count("observed_cycles") ? number("observed_cycles")
                                                     : number("observed_h") * number("cycles_per_h");
  row.point_peaks_MPa.push_back(parse_peaks(field("peaks_MPa"), file, line, col.at("peaks_MPa") + 1));
  if (col.count("stress_fidelity") && !field("stress_fidelity").empty())
    row.stress_fidelity = core::fidelity_from_string(field("stress_fidelity"), "stress_fidelity", file, line,
                                                     col.at("stress_fidelity") + 1);
  if (col.count("runout")) {
    const std::string& r = field("runout");
    if (r != "" && r != "0" && r != "1")
      throw core::InputError("runout '" + r + "' is not 0 or 1 (1: the test stopped without failing)", file, line,
                             col.at("runout") + 1, "runout");
    row.runout = r == "1";
  }
  return row;
}

}  // namespace

std::vector<ObservedLife> parse_observed_lives(const std::string& text, const std::string& file) {
  Columns col;
  std::vector<ObservedLife> out;
  std::map<std::string, std::size_t> by_case;
  std::map<std::string, std::pair<bool, int>> runout_of;  // case name → (runout, first line)
  for (const data::CsvLine& l : data::split_csv_lines(text, file)) {
    if (data::is_blank_or_comment(l.text)) continue;
    const std::vector<std::string> f = data::split_csv_fields(l.text, file, l.number);
    if (col.empty()) {
      col = header_columns(f, file, l.number);
      continue;
    }
    ObservedLife row = read_life_row(f, col, file, l.number);
    // A runout lists each mode's points: one case per mode under its name.
    const std::string key = row.runout ? row.name + '\n' + to_string(row.mode) : row.name;
    if (const auto [seen, fresh] = runout_of.emplace(row.name, std::make_pair(row.runout, l.number));
        !fresh && seen->second.first != row.runout)
      throw core::InputError("case '" + row.name + "' is a " + (row.runout ? "runout" : "failure") + " here and a " +
                                 (row.runout ? "failure" : "runout") + " on line " + std::to_string(seen->second.second),
                             file, l.number, col.at("runout") + 1, "runout");
    auto it = by_case.find(key);
    if (it == by_case.end()) {
      by_case[key] = out.size();
      out.push_back(std::move(row));
      continue;
    }
    // A further row of a case adds a point; the case's mode, temperature, life and runout must agree.
    ObservedLife& c = out[it->second];
    if (c.mode != row.mode || c.temperature_C != row.temperature_C || c.runout != row.runout ||
        c.observed_cycles != row.observed_cycles || c.stress_fidelity != row.stress_fidelity)
      throw core::InputError("case '" + row.name + "' disagrees with its row on line " +
                                 std::to_string(c.line) + " (mode, temperature, life, stress_fidelity or runout)",
                             file, l.number, col.at("case") + 1, "case");
    c.point_peaks_MPa.push_back(row.point_peaks_MPa.front());
  }
  if (out.empty()) throw core::InputError("no observed lives", file, 1, 0);
  check_one_stress_fidelity(out, file);
  return out;
}

void check_one_stress_fidelity(const std::vector<ObservedLife>& cases, const std::string& source) {
  auto at = [](const std::optional<core::Fidelity>& level) {
    return level ? "the " + std::string(core::to_string(*level)) + " level" : std::string("no stated level");
  };
  for (std::size_t k = 0; k < cases.size(); ++k)
    for (std::size_t j = 0; j < k; ++j)
      if (cases[j].mode == cases[k].mode && cases[j].stress_fidelity != cases[k].stress_fidelity)
        throw core::InputError("case '" + cases[k].name + "' (" + to_string(cases[k].mode) + ") has stresses of " +
                                   at(cases[k].stress_fidelity) + ", case '" + cases[j].name + "' (line " +
                                   std::to_string(cases[j].line) + ") of " + at(cases[j].stress_fidelity) +
                                   ": one mode's constants are fitted to the stresses of one level (the scenes' "
                                   "[life] fidelity, or the stress_fidelity column)",
                               source, cases[k].line, 0, "stress_fidelity");
}

namespace {
// The material a mode's cracks run in: mode 1 the bottom rubber, mode 2 the cushion (Report I).
Role role_of(Mode mode) { return mode == Mode::radial_crack ? Role::bottom : Role::cushion; }
}  // namespace

bool has_peaks(Mode mode, const std::vector<PointHistory>& points, const FatigueCard& card,
               const LifeConditions& conditions) {
  for (const PointHistory& p : points)
    if (p.role == role_of(mode) && !cycle_peaks_MPa(p, card.crack_sweep_deg, conditions).empty()) return true;
  return false;
}

ObservedLife observed_life(const std::string& name, Mode mode, double observed_cycles,
                           const std::vector<PointHistory>& points, const FatigueCard& card,
                           const LifeConditions& conditions) {
  ObservedLife c;
  c.name = name;
  c.mode = mode;
  c.temperature_C = conditions.temperature_C;
  c.observed_cycles = observed_cycles;
  for (const PointHistory& p : points)
    if (p.role == role_of(mode)) {
      std::vector<double> peaks = cycle_peaks_MPa(p, card.crack_sweep_deg, conditions);
      if (!peaks.empty()) c.point_peaks_MPa.push_back(std::move(peaks));
    }
  if (c.point_peaks_MPa.empty())
    throw core::InputError("no monitored point of case '" + name + "' has a peak of mode " +
                           to_string(mode), "", 0, 0, "points");
  return c;
}

std::string observed_lives_csv(const std::vector<ObservedLife>& cases) {
  bool levels = false, runouts = false;  // the columns only when a case states its level / is a runout
  for (const ObservedLife& c : cases) levels = levels || c.stress_fidelity.has_value(), runouts = runouts || c.runout;
  std::string out = std::string("case,failure_mode,temperature_C,observed_cycles,point,peaks_MPa") +
                    (levels ? ",stress_fidelity" : "") + (runouts ? ",runout" : "") + "\n";
  for (const ObservedLife& c : cases)
    for (std::size_t k = 0; k < c.point_peaks_MPa.size(); ++k) {
      std::string peaks;
      for (double p : c.point_peaks_MPa[k])
        peaks += (peaks.empty() ? "" : ";") + data::format_exact(p);
      out += data::quote_csv_field(c.name) + "," + to_string(c.mode) + "," +
             data::format_exact(c.temperature_C) + "," + data::format_exact(c.observed_cycles) +
             ",p" + std::to_string(k + 1) + "," + peaks + (levels ? "," + std::string(c.stress_fidelity ? core::to_string(*c.stress_fidelity) : "") : "") +
             (runouts ? (c.runout ? ",1" : ",0") : "") + "\n";
    }
  return out;
}

std::vector<ObservedLife> read_observed_lives(const std::string& path) {
  return parse_observed_lives(core::read_file(path), path);
}

}  // namespace fitlib::fatigue
