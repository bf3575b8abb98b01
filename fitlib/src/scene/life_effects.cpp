// Life effects of a scene (docs/fatigue.md "Life of a scene"): the fidelity level, the stress
// histories at the monitored points (beam level; the segment levels once they land) and the
// fatigue life on them.
#include "card_reading.hpp"
#include "effects.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/progress.hpp"
#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/scene/segment_life.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/segment/point_law.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace fitlib::scene {
namespace detail {
namespace {

// Where the elastic level reads the amplitude-dependent cards ([life] elastic_amplitude).
LifeSpec::ElasticAmplitude elastic_reading(const Scene& s) {
  return s.life ? s.life->elastic_amplitude : LifeSpec{}.elastic_amplitude;
}

// What the life took from a material card, read off the stiffness sources.
std::string card_use(const Scene& s, const SceneResult& r, const std::string& role) {
  const std::string path = s.materials.at(role);
  std::string use;
  auto add = [&](const std::string& source, const char* what) {
    if (source.rfind("card " + path, 0) == 0) use += (use.empty() ? "" : ", ") + std::string(what);
  };
  if (r.stiffness) {
    add(r.stiffness->c_source, "cord stiffness c");
    add(r.stiffness->k1_source, "radial stiffness k1");
    add(r.stiffness->EI_source, "bending stiffness EI (and the beam level's layer moduli EI/I)");
  }
  // The segment levels make the bottom and cushion rubber's material points from their cards
  // (segment_materials below).
  const core::Fidelity fidelity = r.plan.life->fidelity;
  if (fidelity != core::Fidelity::beam && (role == "bottom" || role == "cushion"))
    use += std::string(use.empty() ? "" : ", ") +
           (fidelity == core::Fidelity::elastic ? std::string("segment FE material (storage stiffness at the scene's temperature and load "
                                                "frequency") +
                                        (!r.amplitude_iteration ? ""
                                         : r.amplitude_iteration->per == "element" ? ", each element at the strain amplitude it reached"
                                                                                   : ", at the strain amplitude the segment reached") +
                                        (r.segment_damage_held.count(role) ? ", damage held at its tests' drivers" : "") + ")"
                                  : std::string("segment FE material (the card's full model") +
                                        (r.segment_damage_held.count(role) ? ", damage held at its tests' drivers" : "") + ")");
  if (use.empty()) use = std::string("not read at fidelity ") + core::to_string(fidelity);
  return use;
}

// Work cap of the segment levels (docs/reliability.md §4): element-increments of one run. The
// dearest rate measured, 0.94 ms CPU each (complete level, 450 elements), gives 94 s at the cap;
// it admits the segments that N2 needs (54 mm, 272 elements, 3 cycles: 50 048; 81 mm: 73 600;
// docs/segment.md §Cost), and the defaults (192 elements, 3 cycles: 35 328; the complete level's 180:
// 33 120).
constexpr double kMaxSegmentLifeWork = 1e5;

// Refuses a run beyond the cap before the FE starts, naming the scene and the keys that set it.
void check_segment_work(const Scene& s, const scene::SegmentLifeSetup& setup) {
  const double work = scene::segment_run_work(setup);
  if (work <= kMaxSegmentLifeWork) return;
  const auto& c = setup.cycle.stepping;
  const double elements = work / segment::planned_increments(c);
  const std::string mesh = s.segment && s.segment->life_mesh_changed
                               ? "the life's mesh with the [segment] mesh keys (fine_size_mm, coarse_size_mm, "
                                 "central_pitches, end_pitches, cushion_rows, gap_size_mm, column_growth, row_growth)"
                               : "the life's default mesh";
  throw core::InputError("cycles " + std::to_string(c.cycles) + " x " + std::to_string(c.steps_per_cycle) +
                             " steps per cycle (+ " + std::to_string(c.bend_steps) + " bending steps) x " +
                             core::short_number(elements) + " elements of " + mesh + " = " +
                             core::short_number(work) + " element-increments exceeds the work cap " +
                             core::short_number(kMaxSegmentLifeWork) +
                             " (~90 s of CPU; docs/reliability.md §4): fewer cycles or a coarser mesh",
                         s.path, 0, 0, "life.cycles");
}

// Both levels' first check: a standing belt has no load cycle (nor load frequency, nor hours).
void require_running_belt(const Scene& s, const belt::DriveCase& drive) {
  if (drive.belt_speed_mm_s > 0.0) return;
  std::size_t driver = 0;
  while (driver + 1 < s.pulleys.size() && s.pulleys[driver].role != belt::PulleyRole::driver) ++driver;
  throw core::InputError("a life needs a running belt: the driver's speed_rpm is " +
                             std::string(s.pulleys[driver].speed_rpm ? "0" : "not given") +
                             ", and a standing belt has no load cycle, load frequency or hours",
                         s.path, 0, 0, "drive.pulleys[" + std::to_string(driver) + "].speed_rpm");
}

InputFile file_input(const std::string& role, const std::string& path, const std::string& use) {
  return {role, path, core::sha256_hex(core::read_file(path)), use};
}

// The damage hold for a damage card (docs/decisions.md "Complete level: damage held beyond the tested
// amplitudes", "Life: one policy for a card driven beyond its tests"): the drivers its tests reached
// (fit.data_window.damage_driver) unless [life] beyond_tests = "extrapolate" ("refuse" runs held and
// refuses afterwards); strain_window_warnings says so beside the lives.
std::vector<double> damage_hold(const Scene& s, const card::Card& c) {
  if (s.life && s.life->beyond_tests == LifeSpec::BeyondTests::extrapolate) return {};
  return card::DataWindow(c).damage_drivers();
}

// The elastic equivalent at an amplitude (model::PointOptions::strain_amplitude), which
// segment::RoleMaterialOptions does not carry.
model::MaterialPointPtr elastic_point_at(const model::Model& m, const std::vector<double>& values,
                                         const segment::RoleMaterialOptions& o, const model::Vector6& amplitude) {
  model::PointOptions po;
  po.fidelity = core::Fidelity::elastic;
  po.temperature_C = o.temperature_C, po.frequency_Hz = o.frequency_Hz, po.bulk_modulus_MPa = o.bulk_modulus_MPa;
  po.damage_driver_hold = o.damage_driver_hold;
  po.strain_amplitude = amplitude;
  return model::make_material_point(m, values, po);
}

}  // namespace

model::MaterialPointPtr card_point(const Scene& s, const std::string& role, segment::RoleMaterialOptions options,
                                   std::vector<std::string>& warnings, bool* damage_held,
                                   const std::optional<model::Vector6>& amplitude) {
  const card::Card c = material_card(s, role);
  const model::ModelPtr model = c.model();
  const std::vector<double> values = c.values();
  model::TestCondition at;
  at.temperature_C = options.temperature_C, at.frequency_Hz = options.frequency_Hz;
  model::TestCondition seen = at;  // the complete level's points see the temperature, not one frequency
  if (options.fidelity == core::Fidelity::complete) seen.frequency_Hz = NAN;
  card_window_warnings(s, role, c, seen, warnings);
  if (model->amplitude_dependent() && (options.fidelity == core::Fidelity::complete || amplitude))
    options.damage_driver_hold = damage_hold(s, c);
  if (damage_held) *damage_held = !options.damage_driver_hold.empty();
  try {  // what the card cannot give (a uniaxial card at the complete level, ...) is the scene's input
    options.bulk_modulus_MPa = card::point_bulk_modulus_MPa(*model, values, at, s.material_poisson_ratio);
    if (amplitude && options.fidelity == core::Fidelity::elastic)
      return elastic_point_at(*model, values, options, *amplitude);
    return segment::role_point(*model, values, options);
  } catch (const core::UsageError& e) {
    throw core::InputError("card " + s.materials.at(role) + ": " + e.what(), s.path, 0, 0, "belt.materials." + role);
  }
}

// The segment levels (docs/segment.md "Loading"): materials per role from the scene's cards at
// the level's fidelity (card_point), or, below the complete level, the [segment] table's E and nu
// when the scene gives no card for the role; `held` gets the roles whose card's damage is held.
std::array<model::MaterialPointPtr, 2> segment_materials(const Scene& s, const belt::DriveCase& drive,
                                                         core::Fidelity fidelity, std::vector<std::string>& warnings,
                                                         std::set<std::string>& held,
                                                         const std::map<std::string, model::Vector6>& amplitudes) {
  std::array<model::MaterialPointPtr, 2> points;
  const auto& roles = kSegmentRoles;
  segment::RoleMaterialOptions options;
  options.fidelity = fidelity;
  options.temperature_C = s.temperature_C;
  options.frequency_Hz = load_frequency_Hz(drive);
  for (int k = 0; k < 2; ++k) {
    if (s.materials.count(roles[k])) {
      bool damage_held = false;
      const auto a = amplitudes.find(roles[k]);
      points[k] = card_point(s, roles[k], options, warnings, &damage_held,
                             a == amplitudes.end() ? std::nullopt : std::optional<model::Vector6>(a->second));
      if (damage_held) held.insert(roles[k]);
    } else {
      if (options.fidelity == core::Fidelity::complete)  // it would run isotropic elasticity under its name
        throw core::InputError(std::string("[life] fidelity = \"complete\" runs the full card models, and the scene "
                                           "names no ") + roles[k] + " card: give one in [belt.materials], or ask "
                                           "for \"elastic\" (the [segment] table's isotropic E and nu)",
                               s.path, 0, 0, std::string("belt.materials.") + roles[k]);
      const segment::IsotropicElastic e = s.segment ? s.segment->setup.materials[k] : segment::IsotropicElastic{};
      points[k] = model::make_material_point(*model::make_model("elastic-iso", nlohmann::json::object()),
                                             {e.E_MPa, e.nu});
    }
  }
  return points;
}

// Path position (mm, within the cycle) of a --field-at request: "entrance" = the first sample with
// side pressure (the first pulley met from the slack span's middle), or a number in [0, L).
double field_position(const std::string& at, const belt::LoadCycle& cycle) {
  if (at == "entrance") {
    for (const belt::LoadSample& q : cycle.samples)
      if (q.p_MPa > 0.0) return q.s_mm;
    throw core::InputError("life field at the entrance: the load cycle has no contact");
  }
  const double s_mm = field_at_mm(at);
  if (!(s_mm < cycle.cycle_length_mm))
    throw core::UsageError("life field at '" + at + "': expected \"entrance\" or a path position in mm within [0, " +
                           core::format_number(cycle.cycle_length_mm) + ")");
  return s_mm;
}

namespace {

// What holds the damage where the complete level folds: nothing to say when a card's damage is held.
std::string damage_hold_remedy(const Scene& s, const std::set<std::string>& held) {
  if (!held.empty()) return "";
  if (s.life && s.life->beyond_tests == LifeSpec::BeyondTests::extrapolate)
    return "; [life] beyond_tests = \"hold\" (the default) holds the damage at the drivers the cards' tests reached";
  return "; a card fitted to its table (fitcli fit) holds the damage at the drivers its tests reached "
         "(fit.data_window.damage_driver), where the reference drives pass";
}

// The segment run; a numerical failure says what the user can do.
segment::CycleResult run_segment(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                                 const scene::SegmentLifeSetup& setup, core::Fidelity fidelity,
                                 const std::string& hold_remedy) {
  try {
    return scene::segment_run(cycle, drive, setup);
  } catch (const core::NumericalError& e) {
    const std::string evidence = setup.solver.diagnose_failure
                                     ? ""
                                     : "; [life] diagnose_failure = true adds the evidence (the stiffness's lowest "
                                       "eigenvalues, a tangent check)";
    // The cause, at every level (docs/segment.md "The accelerated regime's fold"): a stability limit
    // of the section under dead loads that scales with the bottom rubber's shear modulus.
    const std::string cause =
        ". The load path folds: under Report I's dead contact loads the section has a stability limit "
        "proportional to its rubber's shear modulus, the bottom rubber's (the cogs') above all (the base accelerated "
        "drive at the complete level runs with elastic cards of E 8 / 1 MPa, bottom / cushion, and folds at 2 / 4 "
        "MPa, whatever the law), so it folds where the side "
        "pressure is high (a small pulley, a heavy load) or the rubber soft (hot, or damaged: a card's damage law "
        "read far beyond its tests) (docs/segment.md \"The accelerated regime's fold\")" + evidence;
    if (fidelity != core::Fidelity::complete)
      throw core::NumericalError(std::string(e.what()) + cause +
                                 "; [life] fidelity = \"beam\" gives the layered section's life without the FE");
    throw core::NumericalError(std::string(e.what()) + cause + hold_remedy +
                               "; [life] fidelity = \"elastic\" runs the segment with the cards' elastic equivalents");
  }
}

// The strain amplitude the segment drove each role's card at (reached_amplitudes: half the range of
// e11, e22 and the engineering shear 2 e12 over the last cycle, the largest at the role's monitored
// points) against the card's data window: fitted at 1–4.5 %, a damage law read at 10 % is
// extrapolated, and the table says so (docs/fatigue.md §8).
void strain_window_warnings(const Scene& s, const std::map<std::string, ReachedAmplitude>& reached,
                            const std::set<std::string>& held, std::vector<std::string>& warnings) {
  std::map<std::string, double> amplitude;  // by role
  for (const auto& [role, a] : reached) amplitude[role] = a.strain_amplitude;
  for (const auto& [role, a] : amplitude) {
    if (!s.materials.count(role)) continue;
    const card::Card c = material_card(s, role);
    model::TestCondition seen;
    seen.temperature_C = s.temperature_C;
    seen.frequency_Hz = NAN;  // the frequency was checked where the card was made a point
    seen.strain_amplitude = a;
    card_window_warnings(s, role, c, seen, warnings);
    const card::DataWindow window(c);
    if (held.count(role)) {  // a held damage law is not read beyond its hold: say so, and how far the belt went
      std::string drivers;
      for (double d : window.damage_drivers()) drivers += (drivers.empty() ? "" : ", ") + core::format_number(d, 3);
      warnings.push_back("card " + s.materials.at(role) + " (" + role + "): its damage is held at the drivers its tests "
                         "reached (fit.data_window.damage_driver " + drivers + "): the segment does not "
                         "extrapolate the damage law beyond its tests; [life] beyond_tests = \"extrapolate\" runs the law at "
                         "every amplitude (the segment drove it at " + core::format_number(a, 3) + ")");
    } else if (window.reads_unknown_amplitude(a))
      warnings.push_back("card " + s.materials.at(role) + " (" + role + ") " + window.unknown_amplitude_clause() +
                         ", and the segment drove it at " + core::format_number(a, 3) + ": " +
                         window.unknown_amplitude_consequence() +
                         (window.amplitude_dependent() ? "" : "; the life is that of a rubber that does not soften") +
                         " (docs/fatigue.md §8)");
  }
}

// Whether two sets of elastic points have the same stiffness to 1e-6 (relative, largest entry): the
// run of one would give the other's amplitudes to about that, far inside the iteration's 2 %.
bool same_stiffness(const std::array<model::MaterialPointPtr, 2>& a, const std::array<model::MaterialPointPtr, 2>& b) {
  for (int k = 0; k < 2; ++k) {
    if (a[k]->state_size() != 0 || b[k]->state_size() != 0) return false;
    model::Matrix6 Ca, Cb;
    a[k]->update(nullptr, model::Vector6::Zero(), 0.0, NAN, nullptr, &Ca);
    b[k]->update(nullptr, model::Vector6::Zero(), 0.0, NAN, nullptr, &Cb);
    if ((Ca - Cb).cwiseAbs().maxCoeff() > 1e-6 * Ca.cwiseAbs().maxCoeff()) return false;
  }
  return true;
}

// The roles whose card softens with the amplitude, which the elastic level reads where the segment
// drives them. Under "hold" a damage card whose window names no drivers (a card written by hand, as the
// bundled thesis cards) has nothing to hold at: it keeps the small-amplitude stiffness, and a warning
// says so.
std::set<std::string> amplitude_roles(const Scene& s, SceneResult& r) {
  const bool extrapolate = s.life && s.life->beyond_tests == LifeSpec::BeyondTests::extrapolate;
  std::set<std::string> roles;
  for (const char* role : kSegmentRoles) {
    if (!s.materials.count(role)) continue;
    const card::Card c = material_card(s, role);
    if (!c.model()->amplitude_dependent()) continue;
    if (extrapolate || !card::DataWindow(c).damage_drivers().empty()) roles.insert(role);
    else
      r.warnings.push_back("card " + s.materials.at(role) + " (" + role + "): the elastic level reads it at the small "
                           "amplitude: its data window names no damage drivers its tests reached "
                           "(fit.data_window.damage_driver; fitcli fit writes them) to hold the damage law at, and "
                           "[life] beyond_tests = \"extrapolate\" reads the law at the amplitude the segment reaches");
  }
  return roles;
}

// The elastic level's iteration (docs/decisions.md "Elastic level: each card read at the amplitude
// the segment drives it"): each amplitude-dependent card is re-read at the strain amplitude the last
// run reached and the segment rerun, until no role's amplitude changes by more than kTolerance
// (relative) between the run that read it and the run it gave; NumericalError after kMaxRuns runs.
segment::CycleResult read_cards_where_driven(const Scene& s, SceneResult& r, scene::SegmentLifeSetup& setup,
                                             segment::CycleResult run, const std::string& remedy,
                                             std::map<std::string, ReachedAmplitude>& read_at) {
  constexpr double kTolerance = 0.02;
  constexpr int kMaxRuns = 8;
  const std::set<std::string> roles = amplitude_roles(s, r);
  if (roles.empty()) return run;
  AmplitudeIteration it{1, kTolerance, {}};
  for (;;) {
    const std::map<std::string, ReachedAmplitude> reached = reached_amplitudes(run);
    double change = 0.0;
    std::string worst;
    for (const std::string& role : roles) {
      if (!reached.count(role)) continue;
      const double now = reached.at(role).strain_amplitude;
      const double before = read_at.count(role) ? read_at.at(role).strain_amplitude : 0.0;
      const double c = now > 0.0 ? std::abs(now - before) / now : (before > 0.0 ? 1.0 : 0.0);
      if (c >= change) change = c, worst = role + " read at " + core::format_number(before, 4) + ", reached " +
                                           core::format_number(now, 4);
    }
    it.changes.push_back(change);
    if (change <= kTolerance) break;
    if (it.runs == kMaxRuns)
      throw core::NumericalError("the elastic level's cards did not settle at the amplitude the segment drives them: "
                                 "after " + std::to_string(kMaxRuns) + " runs the " + worst + " (change " +
                                 core::format_number(100.0 * change, 3) + " %, tolerance " +
                                 core::format_number(100.0 * kTolerance, 3) + " %); [life] fidelity = \"complete\" "
                                 "runs the cards' full models (docs/decisions.md \"Elastic level: each card read at the "
                                 "amplitude the segment drives it\")");
    std::map<std::string, model::Vector6> amplitudes;
    for (const std::string& role : roles)
      if (reached.count(role)) read_at[role] = reached.at(role), amplitudes[role] = voigt_amplitude(reached.at(role));
    const auto points = segment_materials(s, *r.drive, core::Fidelity::elastic, r.warnings, r.segment_damage_held, amplitudes);
    // Cards held at their tests' drivers give the same stiffness at every amplitude beyond them: the
    // rerun would repeat the last run, so the amplitudes it read are (to 1e-6) those it reached.
    if (same_stiffness(points, setup.materials)) {
      it.changes.push_back(0.0);
      break;
    }
    setup.materials = points;
    try {
      run = run_segment(*r.cycle, *r.drive, setup, core::Fidelity::elastic, remedy);
    } catch (const core::NumericalError& e) {
      std::string read;
      for (const auto& [role, a] : read_at) read += (read.empty() ? "" : ", ") + role + " " + core::format_number(a.strain_amplitude, 3);
      throw core::NumericalError(std::string(e.what()) + ". This was run " + std::to_string(it.runs + 1) +
                                 " of the elastic level's reading of the cards at the amplitude the segment reached (" +
                                 read + "): one secant stiffness per role, that of its most strained point, softens "
                                 "the whole role; [life] elastic_amplitude = \"small\" reads the cards at their "
                                 "small-amplitude stiffness, fidelity = \"complete\" softens each point by its own "
                                 "amplitude");
    }
    ++it.runs;
  }
  r.amplitude_iteration = it;
  return run;
}

// Each element of an amplitude-dependent role read at its own amplitude (`read`, in mesh order): the
// card's elastic equivalent there (null for the other roles' elements, which keep their role's point).
// One card load per role; elements read at the same amplitude share a point.
std::vector<model::MaterialPointPtr> element_points(const Scene& s, const belt::DriveCase& drive,
                                                    const segment::CycleResult& run, const std::set<std::string>& roles,
                                                    const std::vector<ReachedAmplitude>& read) {
  std::vector<model::MaterialPointPtr> points(run.element_means.size());
  for (const std::string& role : roles) {
    const card::Card c = material_card(s, role);
    const model::ModelPtr model = c.model();
    const std::vector<double> values = c.values();
    segment::RoleMaterialOptions o;
    o.fidelity = core::Fidelity::elastic, o.temperature_C = s.temperature_C, o.frequency_Hz = load_frequency_Hz(drive);
    o.damage_driver_hold = damage_hold(s, c);
    model::TestCondition at;
    at.temperature_C = o.temperature_C, at.frequency_Hz = o.frequency_Hz;
    std::map<std::array<double, 3>, model::MaterialPointPtr> shared;
    try {
      o.bulk_modulus_MPa = card::point_bulk_modulus_MPa(*model, values, at, s.material_poisson_ratio);
      for (std::size_t e = 0; e < points.size(); ++e) {
        if (core::to_string(run.element_means[e].role) != role) continue;
        model::MaterialPointPtr& p = shared[read[e].components];
        if (!p) p = elastic_point_at(*model, values, o, voigt_amplitude(read[e]));
        points[e] = p;
      }
    } catch (const core::UsageError& e) {
      throw core::InputError("card " + s.materials.at(role) + ": " + e.what(), s.path, 0, 0, "belt.materials." + role);
    }
  }
  return points;
}

// The elastic level with one secant per element (docs/decisions.md "Elastic level: one secant per
// element"): from the small-amplitude run, each element of an amplitude-dependent role is read at
// the amplitude its own mean strain reached in the last run's last cycle (the measure of a role's
// points: ReachedAmplitude) and the segment rerun, until no element's amplitude differs by more than
// kTolerance of its role's largest element amplitude between the run that read it and the run it gave.
// Where a run's change is larger than the last one's, or a rerun folds (NumericalError), the next
// reading moves only part of the way from the last one that passed (relaxation halved, down to
// kLeastRelaxation; a fold there is the level's NumericalError). NumericalError after kMaxRuns runs. `read_at`
// gets each role's most strained element's reading, `read_range` its elements' smallest and largest.
segment::CycleResult read_cards_per_element(const Scene& s, SceneResult& r, scene::SegmentLifeSetup& setup,
                                            segment::CycleResult run, const std::string& remedy,
                                            std::map<std::string, ReachedAmplitude>& read_at,
                                            std::map<std::string, std::array<double, 2>>& read_range) {
  constexpr double kTolerance = 0.02;
  constexpr int kMaxRuns = 10;
  constexpr double kLeastRelaxation = 0.25;
  const std::set<std::string> roles = amplitude_roles(s, r);
  if (roles.empty()) return run;
  AmplitudeIteration it{1, kTolerance, {}, "element", 1.0};
  std::vector<ReachedAmplitude> read(run.element_means.size());  // zero: the small-amplitude reading of the first run
  double last_change = HUGE_VAL;
  for (;;) {
    const std::vector<ReachedAmplitude> reached = element_amplitudes(run);
    double change = 0.0;
    std::string worst;
    for (const std::string& role : roles) {
      double largest = 0.0;
      for (std::size_t e = 0; e < reached.size(); ++e)
        if (core::to_string(run.element_means[e].role) == role) largest = std::max(largest, reached[e].strain_amplitude);
      for (std::size_t e = 0; e < reached.size(); ++e) {
        if (core::to_string(run.element_means[e].role) != role || !(largest > 0.0)) continue;
        const double c = std::abs(reached[e].strain_amplitude - read[e].strain_amplitude) / largest;
        if (c >= change)
          change = c, worst = role + " element " + std::to_string(e) + " read at " +
                              core::format_number(read[e].strain_amplitude, 4) + ", reached " +
                              core::format_number(reached[e].strain_amplitude, 4) + " (role's largest " +
                              core::format_number(largest, 4) + ")";
      }
    }
    it.changes.push_back(change);
    if (change <= kTolerance) break;
    if (it.runs == kMaxRuns)
      throw core::NumericalError("the elastic level's cards did not settle at the amplitudes the segment's elements "
                                 "reach: after " + std::to_string(kMaxRuns) + " runs the " + worst + " (change " +
                                 core::format_number(100.0 * change, 3) + " % of the role's largest, tolerance " +
                                 core::format_number(100.0 * kTolerance, 3) + " %); [life] fidelity = \"complete\" "
                                 "runs the cards' full models (docs/decisions.md \"Elastic level: one secant per element\")");
    if (change > last_change) it.relaxation = std::max(kLeastRelaxation, 0.5 * it.relaxation);
    last_change = change;
    const std::vector<ReachedAmplitude> last_read = read;  // what the last run that passed read
    for (;;) {  // a rerun that folds is retried with the reading moved a smaller step from the last one
      const double w = it.relaxation;
      for (std::size_t e = 0; e < read.size(); ++e) {
        ReachedAmplitude& a = read[e];
        const ReachedAmplitude &b = reached[e], &from = last_read[e];
        a.strain_amplitude = from.strain_amplitude + w * (b.strain_amplitude - from.strain_amplitude);
        a.deviatoric_norm = from.deviatoric_norm + w * (b.deviatoric_norm - from.deviatoric_norm);
        for (int k = 0; k < 3; ++k) a.components[k] = from.components[k] + w * (b.components[k] - from.components[k]);
      }
      setup.element_materials = element_points(s, *r.drive, run, roles, read);
      try {
        segment::CycleResult next = run_segment(*r.cycle, *r.drive, setup, core::Fidelity::elastic, remedy);
        run = std::move(next);
        break;
      } catch (const core::NumericalError& e) {
        ++it.runs;
        if (w <= kLeastRelaxation || it.runs == kMaxRuns)
          throw core::NumericalError(std::string(e.what()) + ". This was run " + std::to_string(it.runs) +
                                     " of the elastic level's reading of each element's card at the amplitude it "
                                     "reached (relaxation " + core::format_number(w, 2) + "); [life] elastic_amplitude "
                                     "= \"small\" reads the cards at their small-amplitude stiffness, fidelity = "
                                     "\"complete\" runs their full models");
        it.relaxation = std::max(kLeastRelaxation, 0.5 * w);
        ++it.folded;  // a run that folded: no change to report
      }
    }
    ++it.runs;
  }
  for (const std::string& role : roles) {  // what each role's elements were read at, by the run that gave the lives
    std::array<double, 2> range{HUGE_VAL, 0.0};
    for (std::size_t e = 0; e < read.size(); ++e) {
      if (core::to_string(run.element_means[e].role) != role) continue;
      range = {std::min(range[0], read[e].strain_amplitude), std::max(range[1], read[e].strain_amplitude)};
      if (!read_at.count(role) || read[e].strain_amplitude > read_at[role].strain_amplitude) read_at[role] = read[e];
    }
    if (read_at.count(role)) read_range[role] = range;
  }
  r.amplitude_iteration = it;
  return run;
}

// [segment] keys that only `fitcli segment`'s static case reads: the life's run has its own load
// (the load cycle), increments (the cycle's schedule), end faces (sheared) and material points
// (the cards', or the contract's Hencky point for [segment.materials]), so it names what it left.
void static_case_keys_warning(const std::vector<std::string>& keys, std::vector<std::string>& warnings) {
  if (keys.empty()) return;
  std::string list;
  for (const std::string& k : keys) list += (list.empty() ? "" : ", ") + k;
  warnings.push_back("[segment] " + list + (keys.size() == 1 ? " configures" : " configure") +
                     " only `fitcli segment`'s static case and " + (keys.size() == 1 ? "is" : "are") +
                     " not applied by the life: its segment runs the load cycle with its own increments, sheared end "
                     "faces and the material points of the cards (a role without one: the contract's Hencky point "
                     "with [segment.materials] E and nu; docs/segment.md \"Static load cases\")");
}

}  // namespace

void segment_stresses(const Scene& s, SceneResult& r) {
  require_running_belt(s, *r.drive);
  in_scene(s, [&] {
    scene::SegmentLifeSetup setup;
    setup.section = cog_section(s);
    setup.mesh = s.segment ? s.segment->life_mesh : scene::life_mesh();
    setup.solver = s.segment ? s.segment->setup.solver : segment::SolverKnobs{};
    setup.cycle = scene::life_cycle(r.plan.life->fidelity);
    setup.solver.threads = segment_threads(s);
    setup.cycle.stepping.cycles = s.life ? s.life->cycles : setup.cycle.stepping.cycles;
    setup.solver.diagnose_failure = s.life && s.life->diagnose_failure;
    check_segment_work(s, setup);
    setup.cycle.physics.manufactured_radius_mm = r.drive->geometry.belt_length_mm / (2.0 * M_PI);
    setup.materials = segment_materials(s, *r.drive, r.plan.life->fidelity, r.warnings, r.segment_damage_held, {});
    // The design point per mode: the worst of the named points, [segment] points and, with [segment]
    // scan = true, the scanned design regions (Report I §6.4).
    setup.cycle.outputs.scan_design_regions = s.segment && s.segment->scan_design_regions;
    setup.cycle.outputs.record_elements = r.plan.life->fidelity == core::Fidelity::elastic &&
                                          elastic_reading(s) == LifeSpec::ElasticAmplitude::element;
    if (s.segment) {
      setup.extra_points = s.segment->setup.points;
      static_case_keys_warning(s.segment->static_case_keys, r.warnings);
    }
    setup.temperature_C = s.temperature_C;
    for (const std::string& at : s.life_field_at) setup.cycle.outputs.vtk_at_s_mm.push_back(field_position(at, *r.cycle));
    setup.cycle.outputs.vtk_prefix = s.life_field_at.empty() ? "" : s.life_field_prefix;
    std::optional<core::Progress> progress;  // in per cent of the run (the bend and the cycles)
    if (s.segment_progress) {
      progress.emplace(std::string("life: segment (") + core::to_string(r.plan.life->fidelity) + ")", 100);
      setup.cycle.outputs.progress = [&progress, shown = std::size_t{0}](double done) mutable {
        const auto now = static_cast<std::size_t>(100.0 * std::clamp(done, 0.0, 1.0));
        if (now > shown) progress->advance(now - shown), shown = now;
      };
    }
    const std::string remedy = damage_hold_remedy(s, r.segment_damage_held);
    segment::CycleResult run = run_segment(*r.cycle, *r.drive, setup, r.plan.life->fidelity, remedy);
    std::map<std::string, ReachedAmplitude> read_at;  // the elastic level's amplitudes, by role
    std::map<std::string, std::array<double, 2>> read_range;  // per element: by role, the smallest and largest
    using A = LifeSpec::ElasticAmplitude;
    const A reading = elastic_reading(s);
    if (r.plan.life->fidelity == core::Fidelity::elastic && reading == A::role)
      run = read_cards_where_driven(s, r, setup, std::move(run), remedy, read_at);
    if (r.plan.life->fidelity == core::Fidelity::elastic && reading == A::element)
      run = read_cards_per_element(s, r, setup, std::move(run), remedy, read_at, read_range);
    const std::map<std::string, ReachedAmplitude> reached = reached_amplitudes(run);
    r.segment_cards_read = card_readings(s, r.plan.life->fidelity, load_frequency_Hz(*r.drive), reached, read_at);
    for (CardReading& c : r.segment_cards_read)
      if (read_range.count(c.role)) {
        c.read_range = read_range.at(c.role);
        c.elements_read = static_cast<int>(std::count_if(run.element_means.begin(), run.element_means.end(), [&c](const segment::MonitoredHistory& m) {
          return core::to_string(m.role) == c.role;
        }));
      }
    refuse_beyond_tests(s, r.segment_cards_read);
    r.stresses = scene::segment_point_histories(run);
    for (int role = 0; role < 2; ++role)
      r.segment_hysteresis_roles_W[role] =
          run.dissipation_J_mm[role] * r.drive->geometry.belt_length_mm * load_frequency_Hz(*r.drive);
    r.segment_hysteresis_W = r.segment_hysteresis_roles_W[0] + r.segment_hysteresis_roles_W[1];
    if (r.heat && r.heat->segment_runs > 0) r.heat->segment_hysteresis_W = *r.segment_hysteresis_W;
    strain_window_warnings(s, reached, r.segment_damage_held, r.warnings);
    r.segment_equilibrium = segment_equilibrium(run);
    const segment::CycleStepping& stepping = setup.cycle.stepping;
    r.segment_run = SegmentRun{run.elements, stepping.cycles, stepping.steps_per_cycle,
                               stepping.cycles > 1 ? segment::conditioning_increments(stepping) : stepping.steps_per_cycle,
                               run.increments, run.newton_iterations, run.cuts};
    for (std::string& w : r.segment_equilibrium->warnings()) r.warnings.push_back(std::move(w));
    for (std::size_t k = 0; k < s.life_field_at.size(); ++k) {  // <prefix>-<k>.vtk, when the run reached it
      const std::string path = setup.cycle.outputs.vtk_prefix + "-" + std::to_string(k) + ".vtk";
      if (std::count(run.vtk_files.begin(), run.vtk_files.end(), path))
        r.segment_fields.push_back({s.life_field_at[k], setup.cycle.outputs.vtk_at_s_mm[k], path});
    }
    r.life_conditions = scene::segment_conditions(*r.cycle, *r.drive, s.temperature_C, run);
  });
}

void beam_stresses(const Scene& s, SceneResult& r) {
  require_running_belt(s, *r.drive);
  in_scene(s, [&] {
    const fatigue::BeamSection section = fatigue::default_beam_section(*r.drive, s.temperature_C);
    r.stresses = fatigue::beam_stress_histories(*r.cycle, *r.drive, section);
    r.life_conditions = fatigue::cycle_conditions(*r.cycle, *r.drive, s.temperature_C);
  });
}

void fatigue_life(const Scene& s, SceneResult& r) {
  const LifeSpec spec = s.life.value_or(LifeSpec{});
  LifeResult life;
  life.plan = *r.plan.life;
  const char* constants = "life constants of (6.31) per mode";
  fatigue::FatigueCard card;
  if (spec.card.empty()) {
    card = fatigue::default_card();
    life.inputs.push_back({"fatigue", "built-in: fatigue::default_card() = datasets/cards/fatigue-fritzson-1988.json",
                           core::sha256_hex(fatigue::card_to_json(card).dump(2) + "\n"), constants});
  } else {
    card = fatigue::load_card(spec.card);
    life.inputs.push_back(file_input("fatigue", spec.card, constants));
  }
  if (spec.crack_sweep_deg) card.crack_sweep_deg = *spec.crack_sweep_deg;
  if (card.levels.count(life.plan.fidelity))  // the card's constants for this level's stresses (docs/fatigue.md §4)
    life.inputs.back().used_for += std::string("; levels.") + core::to_string(life.plan.fidelity) +
                                   " for a mode fitted at another level";
  card = fatigue::card_at_level(card, life.plan.fidelity);
  for (const char* role : kCardRoles)
    if (s.materials.count(role)) life.inputs.push_back(file_input(role, s.materials.at(role), card_use(s, r, role)));
  life.report = in_scene(s, [&] { return fatigue::evaluate_life(*r.stresses, card, *r.life_conditions); });
  life.distribution = fatigue::life_distribution(life.report, card, *r.life_conditions);
  card_uncertainty(s, r, life);
  const bool history = r.segment_equilibrium && r.segment_equilibrium->history;
  for (std::string& w : fatigue::life_warnings(life.report, history)) r.warnings.push_back(std::move(w));
  if (std::string w = fatigue::stress_fidelity_warning(card, life.plan.fidelity); !w.empty())
    r.warnings.push_back(std::move(w));
  life.equilibrium = r.segment_equilibrium;
  life.segment_run = r.segment_run;
  life.damage_held = !r.segment_damage_held.empty();
  life.cards_read = r.segment_cards_read;
  life.amplitude_iteration = r.amplitude_iteration;
  life.beyond_tests = to_string(spec.beyond_tests);
  mark_lives_beyond_tests(life.cards_read, life.report);
  life.fields = r.segment_fields;
  life.heat = r.heat;
  r.life = std::move(life);
}

}  // namespace detail

double field_at_mm(const std::string& at) {
  if (at == "entrance") return std::numeric_limits<double>::quiet_NaN();
  std::size_t used = 0;
  double s_mm = std::numeric_limits<double>::quiet_NaN();
  try {
    s_mm = std::stod(at, &used);
  } catch (const std::exception&) {
  }
  if (used != at.size() || !(s_mm >= 0.0 && std::isfinite(s_mm)))
    throw core::UsageError("life field at '" + at + "': expected \"entrance\" or a path position in mm (>= 0, within "
                           "the load cycle)");
  return s_mm;
}

void check_life_fields(const Scene& s) {
  if (s.life_field_at.empty()) return;
  const LifePlan plan = choose_life_plan(s);
  if (plan.fidelity == core::Fidelity::beam)
    throw core::UsageError("life fields (fitcli life --field-at) need the segment FE ([life] fidelity = \"elastic\" or "
                           "\"complete\"); this scene runs the beam level (" + plan.reason + ")");
  for (const std::string& at : s.life_field_at) field_at_mm(at);
}

SegmentEquilibrium segment_equilibrium(const segment::CycleResult& run) {
  SegmentEquilibrium check{run.equilibrium_error, run.span_cord_share, run.span_section_mismatch, 0,
                           segment::span_cord_share_bound(run), run.history};
  for (const segment::IncrementLoads& q : run.loads) check.span_increments += q.span;
  return check;
}

bool SegmentEquilibrium::in_equilibrium() const {
  using B = segment::EquilibriumBounds;
  return equilibrium_error <= B::equilibrium_error && span_section_mismatch <= B::span_section_mismatch;
}

bool SegmentEquilibrium::within_bounds() const { return in_equilibrium() && span_cord_share <= span_cord_share_bound; }

std::vector<std::string> SegmentEquilibrium::warnings() const {
  if (!in_equilibrium())
    return {"the segment's equilibrium check exceeds its bounds: the stresses are not in equilibrium to the stated "
            "tolerance (docs/segment.md \"Cord-line reactions\")"};
  if (!within_bounds())
    return {"the cord line carries more of the belt force in the spans than its bound (" +
            core::format_number(span_cord_share, 3) + " of F/B against " + core::format_number(span_cord_share_bound, 3) +
            "): " +
            (history ? std::string("the rubber's relaxation in the spans passes stress to the cord line (a card that "
                                   "relaxes slowly, as a fractional Zener's power law, more than the thesis cards' "
                                   "0.8-1.0e-3), or ")
                     : std::string()) +
            "the segment's ends or its length disturb the middle (docs/segment.md \"Cord-line reactions\")"};
  return {};
}

LifePlan choose_life_plan(const Scene& s) {
  if (s.life && s.life->fidelity)
    return {*s.life->fidelity, std::string("[life] fidelity = ") + core::to_string(*s.life->fidelity)};
  const bool cards = s.materials.count("bottom") && s.materials.count("cushion");
  if (!cards && !s.segment)
    return {core::Fidelity::beam, "default: the scene gives neither bottom and cushion cards nor a [segment] table"};
  const std::string why = cards ? "the scene gives bottom and cushion cards, so the segment FE runs with the cards' "
                                   "elastic equivalents"
                                 : "the scene has a [segment] table, so the segment FE runs with its elastic materials";
  // The elastic level takes about 1 s CPU per segment run (thesis cards, 2 cycles, life mesh); the complete
  // level 3-4 s with the damage held (docs/segment.md "Cost (reference)"), and it stops at the fold on
  // 9 of the 13 bundled accelerated drives (docs/segment.md "Known limits").
  return {core::Fidelity::elastic, "default: " + why + " (about 1 s a segment run; the cards are read at their smallest "
                     "tested amplitude and the lives with the level's calibrated constants, [life] elastic_amplitude "
                     "= \"element\" reads each element's card at the amplitude it reaches, iterated, 3-7 runs); "
                     "[life] fidelity = \"complete\" runs the full card models (3-4 s a drive; the load path folds on "
                     "most accelerated-test drives: docs/segment.md \"Known limits\"), \"beam\" the layered "
                     "section (milliseconds)"};
}

}  // namespace fitlib::scene
