// One row of a sweep: run the case's scene with the outputs its columns need, print the columns
// (docs/sweep.md "Columns").
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/sweep.hpp"
#include "sweep_case.hpp"

namespace fitlib::scene {
namespace {

using Column = std::function<std::string(const SceneResult&)>;

// Finite numbers by the one formatter; an unbounded life (or no value) is an empty field.
std::string number(double x) { return std::isfinite(x) ? core::format_number(x) : std::string(); }

double max_over(const belt::LoadCycle& c, double belt::LoadSample::*field, bool absolute = false) {
  double m = -INFINITY;
  for (const auto& s : c.samples) m = std::max(m, absolute ? std::abs(s.*field) : s.*field);
  return m;
}

Column cycle_max(double belt::LoadSample::*field, double scale = 1.0, bool absolute = false) {
  return [=](const SceneResult& r) { return number(scale * max_over(*r.cycle, field, absolute)); };
}

// Life of one failure mode (radial_crack, separation, cord_break); empty when it has none.
Column mode_life(const std::string& mode, bool hours) {
  return [=](const SceneResult& r) {
    const auto& rep = r.life->report;
    if (mode == "cord_break")
      return rep.cord_break ? number(hours ? rep.cord_break->life_h : rep.cord_break->life_cycles) : std::string();
    for (const auto& m : rep.modes)
      if (fatigue::to_string(m.mode) == mode) return number(hours ? m.life_h : m.life_cycles);
    return std::string();
  };
}

// B10 of one mode, or of the governing one (mode ""), in hours; empty when its card states no scatter.
Column b10_hours(const std::string& mode) {
  return [=](const SceneResult& r) {
    const std::string& want = mode.empty() ? r.life->report.governing : mode;
    for (const auto& d : r.life->distribution)
      if (fatigue::to_string(d.mode) == want && d.b10.has_hours) return number(d.b10.h);
    return std::string();
  };
}

struct ColumnSpec {
  const char* output;  // the scene output it needs: load_history or life
  Column column;
  bool text = false;   // a word, not a number (JSON keeps it a string)
};

const std::map<std::string, ColumnSpec>& columns() {
  const double deg = 180.0 / core::kPi;
  static const std::map<std::string, ColumnSpec> table{
      {"max_tension_N", {"load_history", cycle_max(&belt::LoadSample::F_N)}},
      {"min_tension_N", {"load_history", [](const SceneResult& r) {
         double m = INFINITY;
         for (const auto& x : r.cycle->samples) m = std::min(m, x.F_N);
         return number(m);
       }}},
      {"max_side_pressure_MPa", {"load_history", cycle_max(&belt::LoadSample::p_MPa)}},
      {"max_sliding_angle_deg", {"load_history", cycle_max(&belt::LoadSample::gamma_rad, deg, true)}},
      {"max_sliding_speed_mm_s", {"load_history", cycle_max(&belt::LoadSample::slide_mm_s, 1.0, true)}},
      {"max_friction_used", {"load_history", cycle_max(&belt::LoadSample::friction_used)}},
      {"max_sliding_arc_deg", {"load_history", [deg](const SceneResult& r) {
         double m = 0.0;
         for (const auto& p : r.cycle->pulleys) m = std::max(m, p.sliding_rad);
         return number(m * deg);
       }}},
      {"centrifugal_tension_N", {"load_history", [](const SceneResult& r) { return number(r.cycle->centrifugal_tension_N); }}},
      {"cycle_time_s", {"load_history", [](const SceneResult& r) { return number(r.cycle->cycle_time_s); }}},
      {"fidelity", {"life", [](const SceneResult& r) { return std::string(core::to_string(r.life->plan.fidelity)); }, true}},
      {"governing_mode", {"life", [](const SceneResult& r) { return r.life->report.governing; }, true}},
      {"life_cycles", {"life", [](const SceneResult& r) { return number(r.life->report.life_cycles); }}},
      {"life_h", {"life", [](const SceneResult& r) { return number(r.life->report.life_h); }}},
      {"radial_crack_life_cycles", {"life", mode_life("radial_crack", false)}},
      {"radial_crack_life_h", {"life", mode_life("radial_crack", true)}},
      {"separation_life_cycles", {"life", mode_life("separation", false)}},
      {"separation_life_h", {"life", mode_life("separation", true)}},
      {"cord_break_life_cycles", {"life", mode_life("cord_break", false)}},
      {"cord_break_life_h", {"life", mode_life("cord_break", true)}},
      {"B10_h", {"life", b10_hours("")}},
      {"radial_crack_B10_h", {"life", b10_hours("radial_crack")}},
      {"separation_B10_h", {"life", b10_hours("separation")}},
      // the heat balance's belt temperature ([effects] heat_buildup; empty without it)
      {"belt_temperature_C", {"load_history", [](const SceneResult& r) {
         return r.heat ? number(r.heat->temperature_C) : std::string();
       }}},
      {"heat_W", {"load_history", [](const SceneResult& r) { return r.heat ? number(r.heat->heat_in_W) : std::string(); }}},
  };
  return table;
}

// The case's result columns, and its scene's warnings into `warnings` ("; "-joined); InputError /
// NumericalError propagate to the row's status.
std::vector<std::string> result_fields(const Sweep& sweep, Scene scene, std::string& warnings) {
  scene.outputs.clear();  // only what the columns need runs
  for (const auto& c : sweep.columns) scene.outputs[columns().at(c).output] = true;
  const SceneResult r = scene.outputs.count("life") ? run_life(scene) : run_scene(scene);
  if (scene.outputs.count("load_history") && !r.cycle) throw core::InputError("no load cycle", scene.path);
  std::vector<std::string> fields;
  for (const auto& c : sweep.columns) fields.push_back(columns().at(c).column(r));
  for (const std::string& w : r.warnings) warnings += (warnings.empty() ? "warning: " : "; warning: ") + w;
  return fields;
}

}  // namespace

const std::vector<std::string>& sweep_column_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& [name, spec] : columns()) n.push_back(name);
    return n;
  }();
  return names;
}

bool sweep_text_column(const std::string& name) {
  if (name == "scene" || name == "status" || name == "message") return true;
  const auto it = columns().find(name);
  return it != columns().end() && it->second.text;
}

std::vector<std::string> sweep_header(const Sweep& sweep) {
  std::vector<std::string> h{"case", "scene"};
  for (const auto& a : sweep.axes) h.push_back(a.key);
  h.insert(h.end(), sweep.columns.begin(), sweep.columns.end());
  h.push_back("status");
  h.push_back("message");
  return h;
}

namespace {

// A case's message with the files as the sweep file writes them: the scenes and cards are read at
// resolved (absolute) paths, which made the table depend on where it ran (docs/sweep.md "Columns").
std::string as_written(const Sweep& sweep, std::string message) {
  auto replace = [&](const std::string& from, const std::string& to) {
    if (from.empty() || from == to) return;
    for (auto at = message.find(from); at != std::string::npos; at = message.find(from, at + to.size()))
      message.replace(at, from.size(), to);
  };
  for (const auto& a : sweep.axes)
    if (a.key.rfind("belt.materials.", 0) == 0)
      for (std::size_t v = 0; v < a.values.size(); ++v)
        if (const auto* path = std::get_if<std::string>(&a.values[v])) replace(*path, a.labels[v]);
  for (std::size_t k = 0; k < sweep.scenes.size(); ++k) replace(sweep.scenes[k], sweep.scene_labels[k]);
  return message;
}

}  // namespace

std::string sweep_row(const Sweep& sweep, std::size_t index) {
  const SweepCase c = sweep_case(sweep, index);
  std::vector<std::string> fields{std::to_string(index), sweep.scene_labels[c.scene]};
  for (std::size_t a = 0; a < sweep.axes.size(); ++a) fields.push_back(sweep.axes[a].labels[c.value[a]]);
  std::string status = "ok", message;
  std::vector<std::string> results;
  try {
    results = result_fields(sweep, case_scene(sweep, c), message);  // an ok row's message: its warnings
  } catch (const core::InputError& e) {
    status = "input_error", message = e.what();
  } catch (const core::NumericalError& e) {
    status = "numerical_error", message = e.what();
  }
  results.resize(sweep.columns.size());
  fields.insert(fields.end(), results.begin(), results.end());
  fields.push_back(status);
  std::replace(message.begin(), message.end(), '\n', ' ');  // one row per line (resume reads lines)
  fields.push_back(as_written(sweep, message));
  std::string row;
  for (std::size_t i = 0; i < fields.size(); ++i) row += (i ? "," : "") + csv_field(fields[i]);
  return row;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string q = "\"";
  for (char ch : text) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

std::vector<std::string> split_csv_row(const std::string& row) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < row.size(); ++i) {
    const char ch = row[i];
    if (quoted && ch == '"' && i + 1 < row.size() && row[i + 1] == '"') {
      fields.back() += '"', ++i;
    } else if (ch == '"') {
      quoted = !quoted;
    } else if (ch == ',' && !quoted) {
      fields.emplace_back();
    } else {
      fields.back() += ch;
    }
  }
  return fields;
}

}  // namespace fitlib::scene
