#pragma once
// The planner: maps the outputs a scene asks for to the effects they need, adds the refinements
// listed true in [effects], runs only those and reports per effect whether it ran, why, and its
// wall time. Outputs that belong to a later version (life: segment FE and fatigue) are listed as
// not run with the reason "not available in this version" (docs/decisions.md).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/belt/accumulation.hpp"
#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/belt/viscoelastic.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitlib::scene {

struct EffectReport {
  std::string name;
  bool ran = false;
  double wall_s = 0.0;
  std::string reason;  // "needed by load_history", "[effects] inertia = true", "not requested", ...
};

struct Plan {
  std::vector<EffectReport> effects;  // in run order, each with ran = false until run
  belt::LoadCycleEffects load_cycle;
  bool load_cycle_needed = false;
  bool accumulation = false, cvt = false, viscoelastic = false, tension_test = false;
  std::vector<std::string> unavailable_outputs;  // requested but not in this version
  bool will_run(const std::string& effect) const;
};

Plan make_plan(const Scene& scene);

// Belt stiffnesses c, k1, EI at the scene's temperature: [belt.stiffness] overrides first, then
// material cards (cord → c, bottom → E33 for k1 and E22 for EI), then the Fritzson laws of the
// 0.500 in belt with the project's E0/E1 (belt/stiffness.hpp). `source` says which per quantity.
struct Stiffness {
  double c_N = 0.0, k1_MPa = 0.0, EI_Nmm2 = 0.0;
  std::string c_source, k1_source, EI_source;
};
Stiffness resolve_stiffness(const Scene& scene);

// The drive the scene describes (geometry, tensions, belt, friction, speed).
belt::DriveCase make_drive(const Scene& scene, const Stiffness& stiffness);

struct AccumulationMap {
  double kappa = 0.0, shear_stress_MPa = 0.0;
  std::string spectrum_source;
  std::vector<double> omega_rad_s;
  std::vector<long> cycles;
  std::vector<double> gamma;  // gamma[i_omega * cycles.size() + i_N]
  std::vector<long> critical_cycles;  // per ω, −1 if never (only with a strain limit)
};
// The spectrum a scene names: a shape, or the retardation card of a material role.
belt::RetardationSpectrum scene_spectrum(const Scene& scene, const std::string& spec,
                                         std::string* source = nullptr);
// κ = l/R of the scene's drive: centre distance to the next pulley over the driver's radius.
double drive_kappa(const Scene& scene);
AccumulationMap accumulation_map(const belt::RetardationSpectrum& s, const AccumulationSpec& a,
                                 double kappa);

struct SceneResult {
  Plan plan;
  std::optional<Stiffness> stiffness;
  std::optional<belt::DriveCase> drive;
  std::optional<belt::LoadCycle> cycle;
  std::optional<AccumulationMap> accumulation;
  std::optional<belt::TensionTestResult> tension_test;
  nlohmann::json extra = nlohmann::json::object();  // CVT thrust, viscoelastic drive, ...
  double total_wall_s = 0.0;
};

SceneResult run_scene(const Scene& scene, const belt::LoadCycleOptions& options = {});

// Output text: the load history (s, t, pulley, zone, F, K, p, γ, sliding speed, friction used)
// and the JSON summary (plan, effects with wall times, per-pulley results).
std::string load_history_csv(const SceneResult& r);
std::string accumulation_csv(const AccumulationMap& m);
std::string tension_test_csv(const belt::TensionTestResult& t);
// Wall times only with record_timing (otherwise the same scene gives the same bytes).
nlohmann::json summary_json(const Scene& scene, const SceneResult& r, bool record_timing = false);
// Writes load_history.csv, accumulation.csv, tension_test.csv (each if run) and summary.json into `dir`
// atomically; returns the files written.
// The folder is created first (InputError when it cannot be): call prepare_output_dir before
// running to fail early.
std::vector<std::string> write_outputs(const Scene& scene, const SceneResult& r, const std::string& dir,
                                       bool record_timing = false);

}  // namespace fitlib::scene
