// Life tests: a CSV of drive scenes with observed lives, run to the stresses the fit reads
// (life_tests.hpp; docs/fatigue.md §6 "Life tests").
#include "fitlib/scene/life_tests.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/csv.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene_toml.hpp"
#include "sweep_case.hpp"

namespace fitlib::scene {
namespace {

struct Layout {
  std::map<std::string, int> column;                 // the fixed columns: name → 0-based index
  std::vector<std::pair<std::string, int>> keys;     // scene key columns
  std::size_t fields = 0;
  int line = 0;
};

const std::vector<std::string> kFixed = {"case", "scene", "failure_mode", "observed_h", "observed_cycles"};

std::vector<std::string> header_fields(const std::string& text, const std::string& source, int& line) {
  for (const data::CsvLine& l : data::split_csv_lines(text, source))
    if (!data::is_blank_or_comment(l.text)) {
      line = l.number;
      return data::split_csv_fields(l.text, source, l.number);
    }
  throw core::InputError("no header row", source, 1, 0);
}

Layout read_layout(const std::vector<std::string>& f, const std::string& source, int line) {
  Layout h;
  h.fields = f.size(), h.line = line;
  for (std::size_t k = 0; k < f.size(); ++k) {
    const int column = static_cast<int>(k) + 1;
    const bool fixed = std::find(kFixed.begin(), kFixed.end(), f[k]) != kFixed.end();
    if (!fixed && f[k].find('.') == std::string::npos)
      throw core::InputError("unknown column '" + f[k] + "' (expected case, scene, failure_mode, observed_h or "
                             "observed_cycles, and scene keys with a dot such as conditions.temperature_C)" +
                                 data::unknown_column_hint(f[k]),
                             source, line, column, f[k]);
    const bool seen = h.column.count(f[k]) ||
                      std::any_of(h.keys.begin(), h.keys.end(), [&](const auto& c) { return c.first == f[k]; });
    if (seen) throw core::InputError("duplicate column '" + f[k] + "'", source, line, column, f[k]);
    if (fixed) h.column[f[k]] = static_cast<int>(k);
    else h.keys.emplace_back(f[k], static_cast<int>(k));
  }
  for (const char* need : {"scene", "failure_mode"})
    if (!h.column.count(need)) throw core::InputError(std::string("missing column '") + need + "'", source, line, 0, need);
  if (h.column.count("observed_h") == h.column.count("observed_cycles"))
    throw core::InputError("give one of observed_h and observed_cycles", source, line, 0, "observed_h");
  return h;
}

// A scene key's value as TOML would type it: true/false, an integer, a number, else text.
SweepValue key_value(const std::string& text) {
  if (text == "true" || text == "false") return text == "true";
  std::int64_t i = 0;
  const char* end = text.data() + text.size();
  if (auto [p, ec] = std::from_chars(text.data(), end, i); ec == std::errc() && p == end) return i;
  double x = 0.0;
  if (auto [p, ec] = std::from_chars(text.data(), end, x); ec == std::errc() && p == end) return x;
  return text;
}

LifeTest read_row(const std::vector<std::string>& f, const Layout& h, const std::string& source, int line) {
  if (f.size() != h.fields)
    throw core::InputError("row has " + std::to_string(f.size()) + " fields, header has " + std::to_string(h.fields),
                           source, line, 0);
  auto at = [&](const std::string& c) { return f[h.column.at(c)]; };
  auto col = [&](const std::string& c) { return h.column.at(c) + 1; };
  LifeTest t;
  t.line = line;
  t.name = h.column.count("case") && !at("case").empty() ? at("case") : "line " + std::to_string(line);
  if (at("scene").empty()) throw core::InputError("empty scene", source, line, col("scene"), "scene");
  const std::filesystem::path scene(at("scene"));
  t.scene_path =
      (scene.is_absolute() ? scene : std::filesystem::path(source).parent_path() / scene).lexically_normal().string();
  const auto mode = fatigue::mode_from_string(at("failure_mode"));
  t.runout = at("failure_mode") == "none";
  if (!mode && !t.runout)
    throw core::InputError("failure_mode '" + at("failure_mode") + "' is not radial_crack, separation or none (a "
                           "runout: the test stopped without failing)", source, line, col("failure_mode"), "failure_mode");
  if (mode) t.mode = *mode;
  const std::string life = h.column.count("observed_h") ? "observed_h" : "observed_cycles";
  const double value = data::parse_csv_number(at(life), life, source, line, col(life));
  if (!(value > 0.0)) throw core::InputError(life + " must be positive", source, line, col(life), life);
  (life == "observed_h" ? t.observed_h : t.observed_cycles) = value;
  for (const auto& [key, k] : h.keys)
    if (!f[k].empty()) t.scene_keys.emplace_back(key, key_value(f[k]));
  return t;
}

// The test's scene with its keys set; a key the scene rejects names the CSV's line and column.
Scene test_scene(const LifeTest& t, const std::string& source) {
  toml::table root = parse_scene_toml(core::read_file(t.scene_path), t.scene_path);
  for (const auto& [key, value] : t.scene_keys) {
    try {
      set_key_path(root, key, value);
    } catch (const std::invalid_argument& e) {
      throw core::InputError(e.what(), source, t.line, 0, key);
    }
  }
  Scene s = parse_scene_table(root, t.scene_path);
  s.outputs["life"] = true;
  return s;
}

// What an error of test `t` is prefixed with.
std::string test_place(const LifeTest& t) { return "life test '" + t.name + "' (scene " + t.scene_path + "): "; }

// Within a handler of `e`, an error of test `t`'s scene or run: rethrown at the CSV's line with the
// test and its scene in front, or as it is when it already names the CSV.
[[noreturn]] void rethrow_at_test_line(const core::InputError& e, const LifeTest& t, const std::string& source) {
  if (e.file() == source) throw;
  throw core::InputError(test_place(t) + e.what(), source, t.line, 0, e.key());
}

}  // namespace

bool names_scenes(const std::string& csv_text, const std::string& source) {
  int line = 0;
  const std::vector<std::string> f = header_fields(csv_text, source, line);
  return std::find(f.begin(), f.end(), "scene") != f.end();
}

std::vector<LifeTest> parse_life_tests(const std::string& text, const std::string& source) {
  int header_line = 0;
  const std::vector<std::string> names = header_fields(text, source, header_line);
  const Layout h = read_layout(names, source, header_line);
  std::vector<LifeTest> out;
  std::map<std::string, int> line_of_name;  // one name, one test: --peaks-out groups rows by name
  for (const data::CsvLine& l : data::split_csv_lines(text, source)) {
    if (l.number <= header_line || data::is_blank_or_comment(l.text)) continue;
    out.push_back(read_row(data::split_csv_fields(l.text, source, l.number), h, source, l.number));
    if (const auto [at, fresh] = line_of_name.emplace(out.back().name, l.number); !fresh)
      throw core::InputError("case '" + out.back().name + "' repeats the name of line " + std::to_string(at->second) +
                                 ": give each test its own name (replicates of one drive are separate cases)",
                             source, l.number, h.column.at("case") + 1, "case");
  }
  if (out.empty()) throw core::InputError("no life tests (the file has a header only)", source, header_line, 0);
  return out;
}

void refuse_outputs_on_test_scenes(const std::string& csv_text, const std::string& source,
                                   const std::vector<NamedPath>& outputs) {
  if (!names_scenes(csv_text, source)) return;
  for (const LifeTest& t : parse_life_tests(csv_text, source)) {
    try {
      refuse_outputs_on_inputs(test_scene(t, source), outputs);
    } catch (const core::InputError& e) {
      rethrow_at_test_line(e, t, source);
    }
  }
}

std::vector<fatigue::ObservedLife> observe_life_tests(const std::vector<LifeTest>& tests, const std::string& source,
                                                     const fatigue::FatigueCard& card,
                                                     const LifeTestProgress& progress) {
  std::vector<fatigue::ObservedLife> out;
  for (std::size_t k = 0; k < tests.size(); ++k) {
    const LifeTest& t = tests[k];
    if (progress) progress(t, k + 1, tests.size());
    try {
      const Scene s = test_scene(t, source);
      const SceneResult r = run_scene(s);
      if (!r.stresses || !r.life_conditions)
        throw core::InputError("the scene computes no stresses for a life", t.scene_path, 0, 0, "life");
      const double cycles = t.observed_cycles > 0.0 ? t.observed_cycles
                                                    : t.observed_h * r.life_conditions->cycles_per_hour;
      const std::size_t first = out.size();
      if (t.runout) {  // a bound on each mode with a peak at its points
        for (const fatigue::Mode mode : {fatigue::Mode::radial_crack, fatigue::Mode::separation})
          if (fatigue::has_peaks(mode, *r.stresses, card, *r.life_conditions))
            out.push_back(fatigue::observed_life(t.name, mode, cycles, *r.stresses, card, *r.life_conditions));
      } else {
        out.push_back(fatigue::observed_life(t.name, t.mode, cycles, *r.stresses, card, *r.life_conditions));
      }
      for (std::size_t k = first; k < out.size(); ++k)
        out[k].line = t.line, out[k].stress_fidelity = r.plan.life->fidelity, out[k].runout = t.runout;
    } catch (const core::InputError& e) {
      rethrow_at_test_line(e, t, source);
    } catch (const core::NumericalError& e) {
      throw core::NumericalError(source + ":" + std::to_string(t.line) + ": " + test_place(t) + e.what());
    }
  }
  fatigue::check_one_stress_fidelity(out, source);
  return out;
}

std::vector<fatigue::ObservedLife> observed_cases(const std::string& text, const std::string& source,
                                                  const fatigue::FatigueCard& card, const LifeTestProgress& progress) {
  if (!names_scenes(text, source)) return fatigue::parse_observed_lives(text, source);
  return observe_life_tests(parse_life_tests(text, source), source, card, progress);
}

LifeTestsFit fit_life_tests(const std::string& text, const std::string& source, const std::string& start_path,
                            const fatigue::HeldConstants& held, const LifeTestProgress& progress) {
  const fatigue::FatigueCard start = start_path.empty() ? fatigue::default_card() : fatigue::load_card(start_path);
  LifeTestsFit out;
  out.cases = observed_cases(text, source, start, progress);
  try {
    out.fit = fatigue::fit_life_card(out.cases, start, held);
  } catch (const core::InputError& e) {  // about the cases as a whole: named by the file they came from
    if (!e.file().empty()) throw;
    throw core::InputError(e.detail(), source, 0, 0, e.key());
  }
  fatigue::FatigueCard& card = out.fit.card;
  card.name = "life constants fitted to " + source;
  card.provenance["observed"] = {{"file", source}, {"sha256", core::sha256_hex(text)}, {"cases", out.cases.size()}};
  card.provenance["start_file"] = start_path.empty() ? "built-in: fatigue::default_card()" : start_path;
  return out;
}

}  // namespace fitlib::scene
