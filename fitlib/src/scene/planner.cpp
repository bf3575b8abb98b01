// The planner: reads the effect registry, decides what runs and why, runs it in registry order.
#include "fitlib/scene/planner.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

#include <boost/algorithm/string/join.hpp>

#include "effects.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/scene/registry.hpp"

namespace fitlib::scene {
namespace {

bool flag(const std::map<std::string, bool>& m, const std::string& k) {
  auto it = m.find(k);
  return it != m.end() && it->second;
}

// Why each effect cannot run in this build: its own reason, or the first need that cannot run.
std::vector<std::optional<std::string>> blocked_effects(const Scene& s, const std::vector<Effect>& reg,
                                                        const std::map<std::string, std::size_t>& index) {
  std::vector<std::optional<std::string>> blocked(reg.size());
  for (std::size_t i = 0; i < reg.size(); ++i) {
    if (reg[i].unavailable) blocked[i] = reg[i].unavailable();
    for (const auto& need : reg[i].needs(s)) {
      const auto& b = blocked[index.at(need)];
      if (!blocked[i] && b) blocked[i] = "not available: needs " + need + ", " + *b;
    }
  }
  return blocked;
}

// Who asks for each effect: requested outputs and (through `needs`, walked backwards) the
// effects that will read its result. Refinements do not pull in what they refine; an effect this
// build cannot run does not pull in effects that could (they would run for nothing).
std::vector<std::vector<std::string>> askers(const Scene& s, const std::vector<Effect>& reg,
                                             const std::map<std::string, std::size_t>& index,
                                             const std::vector<std::optional<std::string>>& blocked) {
  std::vector<std::vector<std::string>> by(reg.size());
  for (std::size_t i = 0; i < reg.size(); ++i)
    for (const auto& o : reg[i].outputs)
      if (flag(s.outputs, o)) by[i].push_back(o);
  for (std::size_t i = reg.size(); i-- > 0;) {
    const bool wanted = !by[i].empty() || (!reg[i].effects_key.empty() && flag(s.effects, reg[i].effects_key));
    if (!wanted || !reg[i].refines.empty()) continue;
    for (const auto& need : reg[i].needs(s))  // a blocked effect pulls in only what is blocked too
      if (!blocked[i] || blocked[index.at(need)]) by[index.at(need)].push_back(reg[i].name);
  }
  return by;
}

}  // namespace

const char* to_string(EffectStatus status) {
  switch (status) {
    case EffectStatus::run: return "run";
    case EffectStatus::not_requested: return "not_requested";
    case EffectStatus::not_needed: return "not_needed";
    case EffectStatus::unavailable: return "unavailable";
  }
  return "?";
}

bool Plan::will_run(const std::string& effect) const {
  for (const auto& e : effects)
    if (e.name == effect) return e.status == EffectStatus::run;
  return false;
}

Plan make_plan(const Scene& s) {
  const auto& reg = effect_registry();
  std::map<std::string, std::size_t> index;
  for (std::size_t i = 0; i < reg.size(); ++i) index[reg[i].name] = i;
  Plan p;
  if (flag(s.outputs, "life")) p.life = choose_life_plan(s), check_life_fields(s);
  const auto blocked = blocked_effects(s, reg, index);
  const auto by = askers(s, reg, index, blocked);
  for (std::size_t i = 0; i < reg.size(); ++i) {
    const Effect& f = reg[i];
    EffectReport e{f.name, EffectStatus::not_requested, false, 0.0, "not requested", f.cost};
    std::vector<std::string> why;
    if (!by[i].empty()) why.push_back("needed by " + boost::algorithm::join(by[i], ", "));
    if (!f.effects_key.empty() && flag(s.effects, f.effects_key)) why.push_back("[effects] " + f.effects_key + " = true");
    if (why.empty()) {
    } else if (blocked[i]) {
      e.status = EffectStatus::unavailable, e.reason = *blocked[i];
    } else if (!f.refines.empty() && !p.will_run(f.refines)) {
      e.status = EffectStatus::not_needed, e.reason = "not run: no requested output uses " + f.refines;
    } else {
      e.status = EffectStatus::run, e.reason = boost::algorithm::join(why, "; ");
    }
    if (f.load_cycle_switch) p.load_cycle.*f.load_cycle_switch = e.status == EffectStatus::run;
    p.effects.push_back(e);
  }
  for (const auto& o : output_names()) {
    if (!flag(s.outputs, o)) continue;
    for (std::size_t i = 0; i < reg.size(); ++i)
      if (blocked[i] && std::find(reg[i].outputs.begin(), reg[i].outputs.end(), o) != reg[i].outputs.end()) {
        p.unavailable_outputs.push_back(o);
        break;
      }
  }
  return p;
}

namespace {

SceneResult run_effects(const Scene& s, const belt::LoadCycleOptions& options) {
  core::Stopwatch total;
  SceneResult r;
  r.plan = make_plan(s);
  r.load_cycle_options = options;
  const auto& reg = effect_registry();
  Scene at = s;  // after the heat build-up, every effect runs at the belt's temperature (docs/thermal.md)
  for (std::size_t i = 0; i < reg.size(); ++i) {
    EffectReport& e = r.plan.effects[i];
    if (e.status != EffectStatus::run) continue;
    e.wall_s = reg[i].run(at, r);
    e.ran = true;
    if (r.heat) at.temperature_C = r.heat->temperature_C;
  }
  r.total_wall_s = total.seconds();
  return r;
}

}  // namespace

SceneResult run_life(Scene s) {
  s.outputs["life"] = true;
  SceneResult r = run_scene(s);
  if (r.life) return r;
  std::string why = "the planner did not run the fatigue effect";
  for (const auto& e : r.plan.effects)
    if (e.name == "fatigue") why = e.reason;
  throw core::InputError("the life cannot be computed: " + why, s.path, 0, 0, "life.fidelity");
}

belt::HeatSources heat_sources_of_run(const Scene& s, const SceneResult& r) {
  if (!r.drive || !r.cycle) throw std::logic_error("heat_sources_of_run: the run has no drive and load cycle");
  Scene at = s;
  if (r.heat) at.temperature_C = r.heat->temperature_C;
  return detail::heat_sources(at, *r.drive, *r.cycle, nullptr);
}

SceneResult run_scene(const Scene& s, const belt::LoadCycleOptions& options) {
  try {
    return run_effects(s, options);
  } catch (const core::InputError& e) {  // slipping, self-locking, lift-off, ...: name the scene file
    if (!e.file().empty()) throw;
    throw core::InputError(e.detail(), s.path, 0, 0, e.key());
  } catch (const core::NumericalError& e) {
    throw core::NumericalError(s.path + ": " + e.what());
  }
}

}  // namespace fitlib::scene
