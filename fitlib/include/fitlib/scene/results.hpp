#pragma once
// Typed results of a scene run: one slot per effect's product (docs/belt.md "Planner"). JSON is
// made only by the writers (writers.hpp).
#include <array>
#include <map>
#include <set>
#include <optional>
#include <string>
#include <vector>

#include "fitlib/belt/drive.hpp"
#include "fitlib/core/fidelity.hpp"
#include "fitlib/belt/heat.hpp"
#include "fitlib/belt/load_cycle.hpp"
#include "fitlib/belt/viscoelastic.hpp"
#include "fitlib/fatigue/life.hpp"
#include "fitlib/fatigue/life_distribution.hpp"

namespace fitlib::scene {

// Why an effect does or does not run.
enum class EffectStatus {
  run,            // requested (directly or through an output that needs it)
  not_requested,  // nothing asks for it
  not_needed,     // listed true in [effects], but no requested output uses what it refines
  unavailable,    // asked for, but this build cannot run it (or a need of it cannot run)
};
const char* to_string(EffectStatus status);

struct EffectReport {
  std::string name;
  EffectStatus status = EffectStatus::not_requested;
  bool ran = false;
  double wall_s = 0.0;
  std::string reason;  // "needed by load_history", "[effects] inertia = true", "not requested", ...
  std::string cost;    // how wall_s is measured (the registry's words)
};

// The life the planner will compute: the fidelity level and why it was chosen.
struct LifePlan {
  core::Fidelity fidelity = core::Fidelity::beam;
  std::string reason;    // "[life] fidelity = beam" or the default rule's words
};

struct Plan {
  std::vector<EffectReport> effects;  // in run order (the registry's), each with ran = false until run
  belt::LoadCycleEffects load_cycle;  // the refinements that will run
  std::optional<LifePlan> life;       // when [outputs] life = true
  std::vector<std::string> unavailable_outputs;  // requested but not computable in this build
  bool will_run(const std::string& effect) const;
};

// Belt stiffnesses c, k1, EI at the scene's temperature and where each came from.
struct Stiffness {
  double c_N = 0.0, k1_MPa = 0.0, EI_Nmm2 = 0.0;
  std::string c_source, k1_source, EI_source;
  std::vector<std::string> warnings;  // cards read beyond their data windows (scene::card_window_warnings)
};

// Strain-accumulation map (Zupancic–Emri) over angular velocity × cycles.
struct AccumulationMap {
  double kappa = 0.0, shear_stress_MPa = 0.0;
  std::string spectrum_source;
  std::vector<double> omega_rad_s;
  std::vector<long> cycles;
  std::vector<double> gamma;          // gamma[i_omega * cycles.size() + i_N]
  std::vector<long> critical_cycles;  // per ω, −1 if never (only with a strain limit)
};

// Largest relative pointwise change a load-cycle refinement causes (accuracy versus time).
struct EffectChange {
  double F = 0.0, p = 0.0, gamma = 0.0, K = 0.0, friction_used = 0.0;
};

// Sorge–Cammalleri steady drive on the scene's drive.
struct ViscoelasticTension {
  belt::ThreeParameterBelt belt;
  belt::ViscoelasticDrive solution;
};

// Sorge's CVT formulary (12a,b) on the scene's drive, and the 1-D thrust of the load cycle.
struct CvtThrust {
  double tight_tension_N = 0.0, slack_tension_N = 0.0, groove_half_angle_deg = 0.0;
  double driver_wrap_rad = 0.0, driven_wrap_rad = 0.0;
  double driver_axial_thrust_N = 0.0, driven_axial_thrust_N = 0.0;
  std::optional<double> load_cycle_driver_axial_thrust_N, load_cycle_driven_axial_thrust_N;
};

struct TensionTest {
  belt::ThreeParameterBelt belt;
  belt::TensionTestResult result;
};

// A file that fed the life, named with the sha256 of its bytes (traceability to the lab table
// through the card's own provenance).
struct InputFile {
  std::string role;  // bottom | cushion | cord | fatigue
  std::string path, sha256;
  std::string used_for;
};

// The segment run's equilibrium check (segment::CycleResult, docs/segment.md "Cord-line
// reactions and the belt force"); the segment levels only.
struct SegmentEquilibrium {
  double equilibrium_error = 0.0, span_cord_share = 0.0, span_section_mismatch = 0.0;
  int span_increments = 0;  // increments the span checks saw (none: the checks are vacuous)
  double span_cord_share_bound = 1e-5;  // segment::EquilibriumBounds, by the points' history
  bool history = false;                 // the points carry history (the complete level)
  bool within_bounds() const;
  bool in_equilibrium() const;  // the equilibrium error and the section balance within their bounds
  std::vector<std::string> warnings() const;  // one when a check exceeds its bound, else none
};

// What the segment levels' stresses came from: the mesh's element count, the load cycles and their
// planned steps, and the solver's work (life.json `segment_run`, docs/cli.md `life`).
struct SegmentRun {
  int elements = 0, cycles = 0, steps_per_cycle = 0;
  int conditioning_steps = 0;  // planned steps of each cycle before the last (segment::CycleStepping)
  int increments = 0, newton_iterations = 0, cuts = 0;
};

struct FieldFile {         // a full-field stress written by the segment run
  std::string at;           // as asked: "entrance" or a position in mm
  double s_mm = 0.0;        // path position of the segment's middle in the last cycle
  std::string path;
};

// How the segment levels read a role's card (docs/fatigue.md §8 "The cards at the amplitude the
// segment drives them"): at the elastic level the storage stiffness at the scene's temperature, the
// load frequency and (a card whose moduli depend on the amplitude) the strain amplitude the segment
// reached; at the complete level the card's full model at the temperature.
struct CardReading {
  std::string role, card;
  double temperature_C = 0.0;
  std::optional<double> frequency_Hz;  // elastic level
  // Elastic level, an amplitude-dependent card: the amplitude it was read at, (e11, e22, 2 e12) and
  // its largest component; unset: the small-amplitude stiffness (or the complete level).
  std::optional<std::array<double, 3>> read_at;
  std::optional<double> read_amplitude;
  // Read per element ([life] elastic_amplitude = "element"): the smallest and largest amplitude its
  // elements were read at (read_at, read_amplitude: the largest's) and how many elements.
  std::optional<std::array<double, 2>> read_range;
  int elements_read = 0;
  double reached_amplitude = 0.0;  // half the range of e11, e22, 2 e12 over the last cycle, largest point
  std::optional<double> largest_tested_amplitude;  // the card's fit.data_window.strain_amplitude[1]
  // reached / largest tested, when above 1: the card was read beyond its tests.
  std::optional<double> beyond_tests_factor() const;
};

// The elastic level's iteration to the amplitudes the segment reaches (docs/decisions.md "Elastic
// level: each card read at the amplitude the segment drives it"): runs, the tolerance and each run's
// largest relative change of a role's amplitude.
struct AmplitudeIteration {
  int runs = 0;
  double tolerance = 0.0;
  std::vector<double> changes;
  // "role": one amplitude per role (its largest monitored point's; a change is relative to it);
  // "element": one per element (a change is an element's, relative to its role's largest element
  // amplitude), the reading of each rerun relaxed by `relaxation` (1: none).
  std::string per = "role";
  double relaxation = 1.0;
  int folded = 0;  // "element": reruns that folded and were retried with a smaller step (counted in runs)
};

struct LifeResult {
  LifePlan plan;
  std::vector<InputFile> inputs;
  fatigue::LifeReport report;
  std::optional<SegmentEquilibrium> equilibrium;
  std::optional<SegmentRun> segment_run;
  bool damage_held = false;  // the complete level held a card's damage at its tests' drivers
  std::vector<FieldFile> fields;
  // B10/B50 per mode whose card law states a scatter (docs/fatigue.md §9); empty: medians only.
  std::vector<fatigue::ModeDistribution> distribution;
  std::optional<belt::BeltTemperature> heat;  // [effects] heat_buildup: the temperature the life ran at
  std::vector<CardReading> cards_read;          // the segment levels
  std::optional<AmplitudeIteration> amplitude_iteration;
  std::string beyond_tests;                     // the [life] beyond_tests policy the run took
};

struct SceneResult {
  Plan plan;
  std::optional<Stiffness> stiffness;
  std::optional<belt::DriveCase> drive;
  belt::LoadCycleOptions load_cycle_options;  // as run: the caller's knobs and the planned refinements
  std::optional<belt::LoadCycle> cycle;
  std::map<std::string, EffectChange> effect_changes;  // per load-cycle refinement that ran
  std::optional<ViscoelasticTension> viscoelastic;
  std::optional<AccumulationMap> accumulation;
  std::optional<CvtThrust> cvt;
  std::optional<TensionTest> tension_test;
  std::optional<std::vector<fatigue::PointHistory>> stresses;  // at the monitored points
  std::optional<fatigue::LifeConditions> life_conditions;
  // [effects] heat_buildup: the belt's temperature from its heat balance; every later effect runs
  // at it (planner.cpp), the stiffness, drive and load cycle above are the fixed point's.
  std::optional<belt::BeltTemperature> heat;
  std::optional<SegmentEquilibrium> segment_equilibrium;  // the segment levels' check
  std::optional<SegmentRun> segment_run;
  // The segment's own hysteresis: its rubber's dissipation over the last cycle (segment::CycleResult::
  // dissipation_J_mm) times the belt length and the load frequency, W per belt (docs/thermal.md §1).
  std::optional<double> segment_hysteresis_W;
  std::array<double, 2> segment_hysteresis_roles_W{};  // its bottom and cushion rubbers' shares
  std::set<std::string> segment_damage_held;  // roles whose card's damage the complete level held
  std::vector<FieldFile> segment_fields;
  std::vector<CardReading> segment_cards_read;
  std::optional<AmplitudeIteration> amplitude_iteration;
  std::optional<LifeResult> life;
  double total_wall_s = 0.0;
  // Inputs used beyond what they vouch for: a card evaluated outside its data window (the
  // stiffness's and the segment materials' conditions). Printed and in the JSON when any.
  std::vector<std::string> warnings;
};

}  // namespace fitlib::scene
