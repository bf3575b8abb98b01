#pragma once
// Scenes (formats.md §5): one drive, its belt, the conditions, the effects asked for and the
// outputs wanted, read from TOML with full validation. Every unknown key, wrong type, value
// outside its range or impossible geometry is a core::InputError naming the file, line, column
// and key path.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fitlib/belt/drive.hpp"
#include "fitlib/belt/heat.hpp"
#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/core/fidelity.hpp"
#include "fitlib/scene/indexed_run.hpp"
#include "fitlib/scene/segment_life.hpp"
#include "fitlib/segment/static_case.hpp"

namespace fitlib::scene {

struct PulleySpec {
  std::string name;
  double pitch_diameter_mm = 0.0;
  belt::PulleyRole role = belt::PulleyRole::driven;
  std::optional<double> speed_rpm;             // the driver's speed sets the belt speed
  std::optional<std::pair<double, double>> center_mm;  // multi-pulley drives
  double torque_Nm = 0.0;                      // driven pulleys (0 = share of the remainder)
};

// Work caps (README "Work caps"): each keeps one command under a minute on the 2-core reference
// machine; a scene beyond them is an InputError naming the key.
constexpr double kMaxCoordinate_mm = 1e6;
constexpr double kMaxAccumulationPoints = 1e5;       // cycle_points, omega_points each
constexpr double kMaxAccumulationWork = 1e6;         // cycle_points × omega_points
constexpr double kMaxTensionNodes = 1e4, kMaxTensionSteps = 1e5;
constexpr double kMaxTensionWork = 2e6;              // nodes × steps
constexpr double kMaxSegmentSteps = 1000;            // [segment] steps (load increments)
constexpr double kMaxSegmentWork = 2e4;              // [segment] elements × steps (~10 s)
constexpr double kMaxSegmentThreads = 64;            // [segment] threads (the element loop's)

// Strain accumulation request ([accumulation], Zupancic–Emri).
struct AccumulationSpec {
  double shear_stress_MPa = 1.0;   // τ0 of the tooth-like loading
  long cycles = 10000;             // N_max of the map
  int cycle_points = 50;           // N values (log-spaced 1 … N_max)
  double omega_min_rad_s = 1.0, omega_max_rad_s = 1e4;
  int omega_points = 100;
  std::optional<double> kappa;     // l/R; default from the drive: centre distance / driver radius
  std::string spectrum = "material:bottom";  // a shape name, or "material:<role>" for a card
  std::optional<double> strain_limit;        // critical angular-velocity area
};

// Sorge 2-D CVT thrust request ([cvt]); defaults are the paper's example.
struct CvtSpec {
  double tight_tension_N = 0.0, slack_tension_N = 0.0;  // 0: take from the drive
  double groove_half_angle_deg = 12.8;
  double driver_wrap_rad = 0.0, driven_wrap_rad = 0.0;  // 0: take from the drive
};

// Sorge–Cammalleri load/unload test on the scene's two pulleys ([tension_test]); the centre
// distance is d0, the driver's radius r, the friction f.
struct TensionTestSpec {
  double rate_mm_min = 10.0, load_time_s = 120.0;
  std::optional<double> S_N;  // default: the belt's c
  double tau_T_s = 27.0, tau_eps_s = 40.0;
  int nodes = 200, steps = 1200;
};

// Static segment load case ([segment], fitcli segment); geometry from [belt].
struct SegmentSpec {
  segment::StaticSetup setup;
  segment::StaticLoad load;
  // The static case's load frequency (Hz) for the cards' elastic equivalents ([belt.materials]);
  // unset: the drive's, one load cycle per belt revolution (scene::run_segment_case).
  std::optional<double> frequency_Hz;
  // The life's mesh (scene::life_mesh()) with the [segment] mesh keys the scene gives: a key
  // given changes that knob, the others keep the default.
  segment::MeshKnobs life_mesh = scene::life_mesh();
  bool life_mesh_changed = false;  // a mesh key was given
  // [segment] scan = true: the life's design points are the worst of the design regions' points
  // beside the named ones (segment::CycleOutputs::scan_design_regions); false (the default until the
  // fatigue card's constants are read where they were fitted, docs/decisions.md): the named points.
  bool scan_design_regions = false;
  // The keys given that configure only `fitcli segment`'s static case (load, law, end condition,
  // equal steps): a life run does not apply them and says so (docs/decisions.md "Life: the static
  // case's [segment] keys").
  std::vector<std::string> static_case_keys;
};

// Life request ([life], with [outputs] life = true; docs/fatigue.md "Life of a scene").
struct LifeSpec {
  std::optional<core::Fidelity> fidelity;  // absent: the planner's default
  std::string card;                       // fatigue card path (resolved); empty: the bundled default
  int cycles = 3;                         // load cycles the segment levels run (beam: one exact cycle)
  std::optional<double> crack_sweep_deg;  // overrides the card's mode-1 sweep
  bool diagnose_failure = false;          // a failed segment run says why (SolverKnobs::diagnose_failure)
  // Where the segment drives a card beyond its tests (docs/decisions.md "Life: one policy for a card
  // driven beyond its tests"): hold — a damage card's damage is held at the drivers its tests reached
  // (fit.data_window.damage_driver; model::PointOptions::damage_driver_hold) at both segment levels;
  // extrapolate — the damage law at every amplitude; refuse — the life is refused (exit 3, key
  // life.beyond_tests) where a card is driven beyond its largest tested amplitude. `damage_hold =
  // true | false` is the older spelling of hold | extrapolate.
  enum class BeyondTests { hold, extrapolate, refuse };
  BeyondTests beyond_tests = BeyondTests::hold;
  // Elastic level: where the amplitude-dependent cards are read (docs/decisions.md "Elastic level:
  // each card read at the amplitude the segment drives it", "Elastic level: one secant per element"):
  // small — their small-amplitude stiffness; role ("reached") — one secant per role at the amplitude
  // its most strained monitored point reached (it folds the heavy drive); element — each element's
  // own secant at the amplitude it reached, iterated to consistency (opt-in: it folds two accelerated
  // drives the complete level passes; docs/decisions.md "Elastic level: one secant per element").
  enum class ElasticAmplitude { small, role, element };
  ElasticAmplitude elastic_amplitude = ElasticAmplitude::small;
  // [life] uncertainty = "cards": B10/B50 also get the 90 % interval of lives run on `samples`
  // draws of the material cards' parameters from their covariance, seeded (docs/thermal.md §7).
  bool uncertainty_cards = false;
  // [life] uncertainty = "constants+cards": the draws as above, and a third interval of both sources
  // as one distribution (the draws convolved with the constants' t; docs/thermal.md §7).
  bool uncertainty_combined = false;
  int samples = 100;
  std::uint64_t seed = 1;
};
const char* to_string(LifeSpec::BeyondTests policy);

// The card roles of [belt.materials] (the keys of Scene::materials), in the order the scene reads them.
inline constexpr const char* kCardRoles[3] = {"bottom", "cushion", "cord"};

struct Scene {
  std::string name;
  std::string path;  // file it came from (errors, relative card paths)
  // [drive]
  std::vector<PulleySpec> pulleys;  // empty: no [drive] (a [segment]-only scene, for `fitcli segment`)
  std::optional<double> center_distance_mm;
  std::optional<double> torque_Nm, power_kW;
  belt::TensionRule tension_rule = belt::TensionRule::slack;
  double tension_N = 0.0;
  // [belt]
  std::string section;
  belt::BeltSection belt;  // geometry resolved from the section and overrides
  double cord_area_mm2 = 5.0, bending_inertia_mm4 = 834.0;
  std::map<std::string, double> extra_geometry_mm;  // cog_pitch_mm, cog_depth_mm, ... (kept)
  std::optional<double> c_N, k1_MPa, EI_Nmm2;        // [belt.stiffness] overrides
  std::map<std::string, std::string> materials;      // role → card path (resolved); roles kCardRoles
  // role → parameter values that replace its card's (one draw of [life] uncertainty = "cards")
  std::map<std::string, std::vector<double>> card_values;
  // [belt.materials] poisson_ratio: a card without a bulk modulus gets K from its instantaneous
  // modulus and this ν, as in eval and export (card/conversion.hpp).
  double material_poisson_ratio = card::kDefaultPoissonRatio;
  // [conditions]
  double temperature_C = 20.0;
  double friction = 0.8;
  // The air's temperature; with [effects] heat_buildup = true the belt's temperature is the heat
  // balance's fixed point over it, and temperature_C is not read (docs/thermal.md).
  std::optional<double> ambient_C;
  belt::ThermalOptions thermal;  // [thermal]: the balance's coefficients over their defaults
  // [effects], [outputs]: exactly the keys listed
  std::map<std::string, bool> effects;
  std::map<std::string, bool> outputs;
  std::optional<AccumulationSpec> accumulation;
  std::optional<CvtSpec> cvt;
  std::optional<TensionTestSpec> tension_test;
  std::optional<SegmentSpec> segment;
  std::optional<LifeSpec> life;
  // Full-field stress of the segment levels (VTK) when the segment's middle reaches these path
  // positions in the last load cycle: "entrance" (the first pulley's, where its side pressure
  // starts) or a position in mm; written as <life_field_prefix>-<k>.vtk (fitcli life --field-at).
  std::vector<std::string> life_field_at;
  std::string life_field_prefix;
  // > 0: the segment's element loop runs on at most this many threads (a sweep sets 1: it runs
  // its cases in parallel itself); the results do not depend on it.
  int segment_thread_cap = 0;
  // Where [life] uncertainty = "cards" runs its draws: null, this process's threads
  // (segment_threads); set, that executor (fitcli life under mpirun: the draws across the ranks,
  // fitlib/mpi/sweep_mpi.hpp). The results do not depend on it.
  std::shared_ptr<IndexedExecutor> draw_executor;
  // The segment run's progress (share of the load cycles done) on stderr when it is a terminal
  // (fitcli life without --quiet); never in the outputs.
  bool segment_progress = false;
};

// The segment's element-loop threads: [segment] threads or the solver's default, at most
// Scene::segment_thread_cap when that is set.
int segment_threads(const Scene& scene);

// The cogged section of the scene's belt ([belt] cog_* keys over the section's defaults).
segment::CogSection cog_section(const Scene& scene);

Scene load_scene(const std::string& path);
Scene parse_scene(const std::string& toml_text, const std::string& source_name = "scene");

// Names the scene format accepts.
const std::vector<std::string>& effect_names();
const std::vector<std::string>& output_names();

}  // namespace fitlib::scene
