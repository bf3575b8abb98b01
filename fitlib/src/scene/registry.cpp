// The effect registry: every effect a scene can ask for, declared once (docs/belt.md "Planner").
#include "fitlib/scene/registry.hpp"

#include <algorithm>

#include "effects.hpp"
#include "fitlib/core/timer.hpp"

namespace fitlib::scene {
namespace {

const char* kOneRun = "wall time of one run";

std::function<std::vector<std::string>(const Scene&)> always(std::vector<std::string> names) {
  return [names](const Scene&) { return names; };
}

// Wraps an effect body as a run timed once.
std::function<double(const Scene&, SceneResult&)> timed(std::function<void(const Scene&, SceneResult&)> body) {
  return [body](const Scene& s, SceneResult& r) {
    core::Stopwatch w;
    body(s, r);
    return w.seconds();
  };
}

double wall_of(const SceneResult& r, const std::string& name) {
  for (const auto& e : r.plan.effects)
    if (e.name == name) return e.wall_s;
  return 0.0;
}

// A load-cycle refinement: its cost is the increment of the cycle over the cycle without it,
// its change the largest pointwise change it causes (accuracy versus time).
Effect refinement(const std::string& name, bool belt::LoadCycleEffects::*on) {
  Effect e;
  e.name = name;
  e.produces = "cycle (refined), effect_changes." + name;
  e.cost = "load cycle with it minus without it (best of three each)";
  e.effects_key = name;
  e.needs = always({"contact_arcs"});
  e.refines = "contact_arcs";
  e.load_cycle_switch = on;
  e.run = [name, on](const Scene&, SceneResult& r) {
    belt::LoadCycleOptions without = r.load_cycle_options;
    without.effects.*on = false;
    belt::LoadCycle base;
    const double without_s = detail::best_of_three(*r.drive, without, base);
    r.effect_changes[name] = detail::effect_change(*r.cycle, base);
    return std::max(0.0, wall_of(r, "contact_arcs") - without_s);
  };
  return e;
}

std::vector<Effect> make_registry() {
  std::vector<Effect> reg;
  reg.push_back({"stiffness", "stiffness", kOneRun, {}, "", always({}), "", nullptr, {},
                 timed([](const Scene& s, SceneResult& r) {
                   r.stiffness = resolve_stiffness(s);
                   r.warnings = r.stiffness->warnings;
                 })});
  reg.push_back({"drive", "drive", kOneRun, {}, "", always({"stiffness"}), "", nullptr, {},
                 timed([](const Scene& s, SceneResult& r) { r.drive = make_drive(s, *r.stiffness); })});
  reg.push_back({"contact_arcs", "cycle", "best of three load cycles, its refinements included",
                 {"load_history"}, "", always({"drive"}), "", nullptr, {},
                 [](const Scene&, SceneResult& r) {
                   r.load_cycle_options.effects = r.plan.load_cycle;
                   r.cycle.emplace();
                   return detail::best_of_three(*r.drive, r.load_cycle_options, *r.cycle);
                 }});
  reg.push_back(refinement("bending_zones", &belt::LoadCycleEffects::bending_zones));
  reg.push_back(refinement("inertia", &belt::LoadCycleEffects::inertia));
  reg.push_back(refinement("full_ode", &belt::LoadCycleEffects::full_ode));
  reg.push_back(refinement("driver_exit_ramp", &belt::LoadCycleEffects::driver_exit_ramp));
  reg.push_back({"viscoelastic_tension", "viscoelastic", kOneRun, {}, "viscoelastic_tension",
                 always({"drive"}), "", nullptr, {}, timed([](const Scene& s, SceneResult& r) {
                   const auto inertia = s.effects.find("inertia");
                   const bool with_inertia = inertia != s.effects.end() && inertia->second;
                   r.viscoelastic = detail::viscoelastic_tension(*r.drive, with_inertia);
                 })});
  reg.push_back({"strain_accumulation", "accumulation", kOneRun, {"strain_accumulation"}, "",
                 always({"drive"}), "", nullptr, {}, timed([](const Scene& s, SceneResult& r) {
                   const AccumulationSpec a = s.accumulation.value_or(AccumulationSpec{});
                   std::string source;
                   const auto spectrum = scene_spectrum(s, a.spectrum, &source);
                   r.accumulation = accumulation_map(spectrum, a, a.kappa ? *a.kappa : drive_kappa(s));
                   r.accumulation->spectrum_source = source;
                 })});
  reg.push_back({"cvt_thrust", "cvt", kOneRun, {"cvt_thrust"}, "", always({"drive"}), "", nullptr, {},
                 timed([](const Scene& s, SceneResult& r) {
                   r.cvt = detail::cvt_thrust(*r.drive, s.cvt.value_or(CvtSpec{}), r.cycle ? &*r.cycle : nullptr);
                 })});
  reg.push_back({"tension_test", "tension_test", kOneRun, {"tension_test"}, "", always({"drive"}), "",
                 nullptr, {}, timed([](const Scene& s, SceneResult& r) {
                   r.tension_test = detail::tension_test(*r.drive, s.tension_test.value_or(TensionTestSpec{}), s.friction);
                 })});
  reg.push_back({"heat_buildup", "heat (the belt temperature of its heat balance; stiffness, drive, cycle at it)",
                 "wall time of the fixed point (a stiffness, drive and load cycle per iteration)", {}, "heat_buildup",
                 always({"contact_arcs"}), "", nullptr, {}, timed(detail::heat_buildup)});
  reg.push_back({"beam_stresses", "stresses, life_conditions", kOneRun, {}, "", always({"contact_arcs"}), "",
                 nullptr, {}, timed(detail::beam_stresses)});
  reg.push_back({"segment_fe", "stresses, life_conditions", kOneRun, {}, "", always({"contact_arcs"}), "",
                 nullptr, {}, timed(detail::segment_stresses)});
  reg.push_back({"fatigue", "life", kOneRun, {"life"}, "",
                 [](const Scene& s) {
                   return std::vector<std::string>{choose_life_plan(s).fidelity == core::Fidelity::beam ? "beam_stresses" : "segment_fe"};
                 },
                 "", nullptr, {}, timed(detail::fatigue_life)});
  return reg;
}

}  // namespace

const std::vector<Effect>& effect_registry() {
  static const std::vector<Effect> reg = make_registry();
  return reg;
}

}  // namespace fitlib::scene
