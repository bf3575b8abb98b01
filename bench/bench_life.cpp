// Life accuracy versus time per fidelity level (issue 11; plain main, prints its tables):
// 1. For every bundled reference drive (datasets/drives/ref-0500-*.toml with the thesis-like
//    cards material-1-true (bottom) and material-2-true (cushion)) and every fidelity level of
//    [life]: life per mode, governing mode, wall time of the whole scene run (`fitcli life`'s
//    route, 2 load cycles) and its ratio to the beam row; "complete held" is the complete level with
//    the cards' damage held at what their tables' tests reached (it passes every drive).
// 2. The segment's convergence on the medium drive: life versus mesh (the default 144 elements and
//    a 0.6/2.0 mm mesh), versus the segment's length (27 mm sheared and radial ends, 54, 81 mm) and versus steps per cycle (20/40/80), for Report I's isotropic elastic
//    materials (iso: E 20/8 MPa, ν 0.49, bare drive) and the cards' elastic level, relative to the
//    finer (the complete level stops on the medium drive: its table is 5).
// 3. Time versus elements and versus steps, and the exponent of each (least squares in log–log).
// 4. The beam level's 1000-drive sweep through the planner.
// 5. The complete level's convergence on the light drive (the only reference drive it passes with
//    the damage law at every amplitude):
//    cushion rows, element size, grading and steps against 0.25 mm elements with 3 cushion rows
//    (docs/segment.md "Which segment N1 should be read from"); `bench_life meshconv` prints it alone
//    (~5 min, the reference ~3 of them).
// 6. What heat build-up and the life distribution cost per drive against the run without them
//    (`bench_life heat` prints it alone).
// 7. What [life] uncertainty = "cards" and "constants+cards" cost per drive against the run without
//    them, per draw and in total (`bench_life uncertainty` prints it alone).
// 8. The level calibration's held-out drives (bench/life_calibration.hpp; `bench_life calibration`;
//    its table is headed "Level calibration").
// 9. What the design-point scan ([segment] scan = true) costs per drive and where it puts the design
//    point (`bench_life scan` prints it alone).
// 10. The segment levels' cost per reference drive against a baseline binary in the same run
//    (`bench_life cost [BASELINE_FITCLI] [runs=N]` prints it alone; docs/segment.md "Cost (reference)").
// 11. The heat source per level against the complete level's dissipation (`bench_life heatlevels
//    [temperatures]` prints it alone; not in the default run: minutes per drive).
// `bench_life quick` leaves out the complete level (minutes per drive); `bench_life levels` prints
// table 1 only, complete rows included.
// `bench_life probe LOAD FIDELITY MESH STEPS [reuse] [extrapolate] [stall=N] [grow=N] [cuts=N] [tol=X] [full|fbar|reduced]
// [lagged] [hold] [lm=MU] [diagnose] [fillet=MM] [tip=MM] [set=NAME=VALUE ...]` runs one segment life and prints its counts (LOAD: light | medium | heavy | severe, or a drive
// file of datasets/drives with its .toml; MESH: life or
// coarse (the life's default, both levels) | medium | fine;
// `reuse`: modified Newton, NewtonOptions::reuse_tangent; `extrapolate`: SteppingOptions::extrapolate_start;
// `stall=`, `grow=`: NewtonOptions::stall_iterations, SteppingOptions::growth_iterations (default: the solver's);
// `hold`: the cards' damage held at what their tables' tests reached (RoleMaterialOptions::damage_driver_hold);
// `full`: 3×3 Gauss integration, `fbar`: the F-bar element, `reduced`: CPE8R (default: the
// setup's); `lagged`: PointOptions::DamageUpdate::lagged; `set=`: a parameter of both cards, e.g.
// set=C_d=0.001); `rows=N`, `fine=MM`, `coarse=MM`, `central=P`, `ends=P`: the mesh's cushion rows,
// element sizes and section lengths in cog pitches (after MESH); `fillet=`, `tip=`: the cogs' root
// fillet and tip radius (mm); `diagnose`: SolverKnobs::diagnose_failure (a failure prints the tangent
// check, the lowest eigenvalues and the residual along Newton's direction); `gap=MM`, `cgrowth=X`,
// `rgrowth=R`: the grading knobs gap_size_mm, column_growth, row_growth (docs/segment.md §Mesh);
// `vtk=FILE`: write the mesh (straight reference) as VTK; `profile`: also monitor the cushion at
// x = 0 every tenth of its depth; `land`: also monitor the gap centre line 0.05–1 mm above the gap
// bottom (docs/segment.md "Convergence of the complete level"). The probe
// prints each cushion and land point (its depth below the cord line) and its own life (last cycle's peaks).
// `bc=radial|free|sheared`: the end faces (default: the life's, sheared); `section=X`: also monitor
// x = ±X every 0.5 mm of depth (0.25 … 6.25 mm; these points count in the lives); `csv=PATH`: the
// monitored histories; `oracle=PATH`: the end faces' shear and warping from a longer run's
// section=X CSV (X = this segment's half-length; docs/segment.md "End faces"); `dense=A:B:DS`: the
// planned steps plus one every DS mm of path over [A, B] mm of the last cycle; `bodyds=MM`: the body forces' sampling over each element
// (CyclePhysics::body_force_sampling_mm, 0 = at the element's centre); `inertia`: PhysicsOptions::inertia
// (implicit dynamics, docs/segment.md "Inertia"); `flank=K`: the flank foundation's stiffness
// (CyclePhysics::flank_stiffness_N_mm4, N/mm⁴; 0 = off; docs/segment.md "Flank foundation"); `tflank=K`:
// the tangential flank's stick stiffness (CyclePhysics::flank_stick_N_mm4, N/mm⁴; 0 = off;
// docs/segment.md "Tangential flank"); `vflank=V0`: the sliding friction's direction with this floor of
// the sliding speed (CyclePhysics::flank_slide_floor_mm_s, mm/s; 0 = off); `turn=K`: the friction turned by
// the flank's layer of this k_t (CyclePhysics::flank_turn_N_mm4, N/mm⁴; 0 = off); `branch=X`: the branch switch
// (SteppingOptions::branch_switch: the critical mode's amplitude as a share of the shortest element
// side; 0 = off); `cycles=N`: load cycles (default 2); `loads=A:B`: print the load
// cycle's samples over [A, B] mm of path (zone, p, γ, sliding speed, friction used); `field=PREFIX:MM[:MM…]`: the
// stress field (VTK) when the middle first reaches each path position of the last cycle,
// PREFIX-k.vtk; `threads=N`: the element loop's threads (SolverKnobs::threads;
// default min(2, hardware); every table prints the count it ran with); `krylov=N`, `ktol=X`:
// NewtonOptions::krylov_iterations and krylov_tolerance (GMRES on unsymmetric tangents; krylov=0: the
// LU every time); `plainpressure`: NewtonOptions::linearised_pressure off; `linearpred`:
// SteppingOptions::rotated_predictor off; `keep=X`: NewtonOptions::keep_preconditioner_below (0: a
// factorisation per tangent); `first=N`: CycleStepping::conditioning_steps (0: as the last); `split=0|1`:
// NewtonOptions::split_factorisation. The probe also prints the main thread's CPU time (the critical path).
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/resource.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "baseline_args.hpp"
#include "drive_sweep.hpp"
#include "life_calibration.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/scene/segment_life.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/segment/point_law.hpp"

using namespace fitlib;

namespace {

const std::string kRoot = FITLIB_SOURCE_DIR;
const char* kLoads[] = {"light", "medium", "heavy", "severe"};

// A reference drive's file (light, medium, heavy, severe), or any drive file of datasets/drives
// named with its .toml (the probe's LOAD, e.g. acc-0500-base.toml).
std::string drive_file(const std::string& load) {
  const bool file = load.size() > 5 && load.compare(load.size() - 5, 5, ".toml") == 0;
  return kRoot + "/datasets/drives/" + (file ? load : "ref-0500-" + load + ".toml");
}

scene::Scene reference(const std::string& load) {
  auto s = scene::load_scene(drive_file(load));
  s.materials["bottom"] = kRoot + "/datasets/cards/material-1-true.json";
  s.materials["cushion"] = kRoot + "/datasets/cards/material-2-true.json";
  return s;
}

// The bundled card of `material` ("material-1", "material-2") with the data window of the
// synthetic table drawn from it (datasets/materials/<material>.csv): its window's damage drivers let
// the complete level hold the damage at what those tests reached.
card::Card windowed_card(const std::string& material) {
  card::Card c = card::load_card(kRoot + "/datasets/cards/" + material + "-true.json");
  const data::DynamicTestTable table = data::read_dynamic_table(kRoot + "/datasets/materials/" + material + ".csv");
  c.fit["data_window"] = card::data_window_json(table, c.model().get(), c.values());
  return c;
}

// windowed_card written to a temporary file, for a scene.
std::string windowed_card_file(const std::string& material) {
  const std::string path = "/tmp/fitlib-bench-life-" + std::to_string(::getpid()) + "-" + material + ".json";
  card::save_card(path, windowed_card(material));
  return path;
}

// `level` "complete held": the complete level with the cards' damage held at what their tables'
// tests reached ([life] damage_hold, from windowed_card_file).
scene::Scene life_scene(const std::string& load, const std::string& level) {
  scene::Scene s = reference(load);
  s.outputs = {{"life", true}};
  s.life = scene::LifeSpec{};
  s.life->fidelity = core::fidelity_from_string(level == "complete held" ? "complete" : level, "level");
  if (level == "complete held") {
    static const std::string bottom = windowed_card_file("material-1"), cushion = windowed_card_file("material-2");
    s.materials["bottom"] = bottom, s.materials["cushion"] = cushion;
  }
  s.life->cycles = 2;
  return s;
}

// The segment meshes of the convergence table (docs/segment.md §Cost). "life" and "coarse": the
// life's default (scene::life_mesh(), both levels).
segment::MeshKnobs mesh_named(const std::string& name) {
  segment::MeshKnobs m = scene::life_mesh();
  if (name == "medium") m.fine_size_mm = 0.6, m.coarse_size_mm = 2.0, m.central_pitches = 1, m.end_pitches = 1, m.cushion_rows = 1;
  if (name == "fine") m.fine_size_mm = 0.4, m.coarse_size_mm = 1.5, m.central_pitches = 2, m.end_pitches = 2, m.cushion_rows = 2;
  if (name == "long") m.central_pitches = 2, m.end_pitches = 2;    // the life mesh's sizes, 54 mm long
  if (name == "longer") m.central_pitches = 3, m.end_pitches = 3;  // 81 mm
  return m;
}

struct Probe {
  std::string load = "medium", fidelity = "elastic", mesh = "medium";
  int steps = 60;
  bool reuse = false, extrapolate = false, lagged = false;
  double keep_below = -1.0;  // keep=X: NewtonOptions::keep_preconditioner_below (< 0: the default)
  int split = -1;            // split=0|1: NewtonOptions::split_factorisation (< 0: the default)
  int first_steps = -1;      // first=N: CycleStepping::conditioning_steps (< 0: the life's)
  std::string integration{};  // empty: scene::SegmentLifeSetup's default
  int stall = -1, cuts = segment::SolverKnobs{}.stepping.max_cuts;  // stall=N (< 0: the life's at the fidelity)
  int growth = -1;  // grow=N: SteppingOptions::growth_iterations (< 0: the life's at the fidelity)
  double tolerance = segment::SolverKnobs{}.newton.tolerance;  // tol=X: Newton's relative residual tolerance
  std::vector<std::pair<std::string, double>> overrides{};  // set=NAME=VALUE: a card parameter, both roles
  double levenberg = segment::SolverKnobs{}.newton.levenberg;  // lm=μ0 (0: off)
  int rows = 0;                                 // rows=N: cushion rows (0: the mesh's)
  double fine_mm = 0.0, coarse_mm = 0.0;        // fine=, coarse=: element sizes (0: the mesh's)
  double central = 0.0, ends = 0.0;             // central=, ends=: section lengths in pitches (0: the mesh's)
  double gap_mm = -1.0, column_growth = 0.0, row_growth = 0.0;  // gap=, cgrowth=, rgrowth= (≤ 0 / −1: the mesh's)
  std::string vtk{};                            // vtk=FILE: the mesh as VTK
  bool profile = false;                         // monitor the cushion at x = 0, every tenth of its depth
  bool land = false;                            // monitor the land above the gap bottom (x = 0)
  bool diagnose = false;                        // SolverKnobs::diagnose_failure
  double fillet_mm = -1.0, tip_mm = -1.0;       // fillet=, tip=: the cogs' root fillet and tip radius (< 0: the scene's)
  std::string end_condition{};                  // bc=radial|free (empty: the setup's)
  double section_x = -1.0;                      // section=X: monitor x = ±X every 0.5 mm of depth
  std::string csv{};                            // csv=PATH: the monitored histories
  std::string oracle{};                         // oracle=PATH: end shear from a long run's section= CSV
  std::array<double, 3> dense{0.0, 0.0, 0.0};   // dense=A:B:DS: also every DS mm over [A, B] of the last cycle
  std::array<double, 2> loads{0.0, 0.0};        // loads=A:B: print the load cycle's samples over [A, B] mm first
  int threads = 0;                              // threads=N: SolverKnobs::threads (0: the default)
  int krylov = -1;                              // krylov=N: NewtonOptions::krylov_iterations (< 0: the default)
  bool plain_pressure = false;                  // plainpressure: NewtonOptions::linearised_pressure off
  bool linear_predictor = false;                // linearpred: SteppingOptions::rotated_predictor off
  double krylov_tolerance = -1.0;               // ktol=X: NewtonOptions::krylov_tolerance (< 0: the default)
  double body_sampling_mm = -1.0;               // bodyds=MM: CyclePhysics::body_force_sampling_mm (< 0: the default)
  bool inertia = false;                         // PhysicsOptions::inertia
  bool hold = false;                            // hold: the cards' damage held at their tables' tests (windowed_card)
  int cycles = 2;                               // cycles=N
  double flank = -1.0;                          // flank=K: CyclePhysics::flank_stiffness_N_mm4 (< 0: the setup's)
  double tflank = -1.0;                         // tflank=K: CyclePhysics::flank_stick_N_mm4 (< 0: the setup's)
  double vflank = -1.0;                         // vflank=V0: CyclePhysics::flank_slide_floor_mm_s (< 0: the setup's)
  double turn = -1.0;                           // turn=K: CyclePhysics::flank_turn_N_mm4 (< 0: the setup's)
  double branch = 0.0;                          // branch=X: SteppingOptions::branch_switch (0: off)
  std::string field_prefix{};                   // field=PREFIX:MM[:MM…]
  std::vector<double> field_at_mm{};
};

// The end faces' shear (column 0) or warping (column 1) from a longer run's CSV (section=X there,
// X = this segment's half-length): σ12 or −∫ 2 e12 dh of left-k / right-k (depth 0.25 + 0.5k mm)
// against the middle's path position, linear in both.
std::function<double(int, double, double)> oracle_end(const std::string& path, int column) {
  std::array<std::vector<std::vector<std::pair<double, double>>>, 2> table;
  for (auto& t : table) t.resize(13);
  std::FILE* f = std::fopen(path.c_str(), "r");
  char line[1024];
  while (f && std::fgets(line, sizeof line, f)) {
    char name[64];
    double v[11];
    if (std::sscanf(line, "%63[^,],%*[^,],%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", name, v, v + 1, v + 2, v + 3,
                    v + 4, v + 5, v + 6, v + 7, v + 8, v + 9, v + 10) != 12)
      continue;
    const std::string n = name;
    const int side = n.rfind("left-", 0) == 0 ? 0 : n.rfind("right-", 0) == 0 ? 1 : -1;
    if (side >= 0) table[side][std::atoi(n.c_str() + (side ? 6 : 5))].emplace_back(v[3], column == 0 ? v[6] : v[10]);
  }
  if (f) std::fclose(f);
  return [table, column](int side, double depth, double s) {
    auto at = [&](int k) {
      const auto& v = table[side][k];
      auto it = std::lower_bound(v.begin(), v.end(), std::make_pair(s, -1e300));
      if (it == v.begin()) return v.front().second;
      if (it == v.end()) return v.back().second;
      const auto& a = *(it - 1);
      const double w = it->first > a.first ? (s - a.first) / (it->first - a.first) : 1.0;
      return a.second + w * (it->second - a.second);
    };
    const double u = std::clamp((depth - 0.25) / 0.5, 0.0, 12.0);
    const int k = std::min(11, static_cast<int>(u));
    if (column == 0) return at(k) + (u - k) * (at(k + 1) - at(k));
    double w = -2.0 * at(0) * std::min(depth, 0.25);  // −∫ 2 e12 dh, trapezoids between the samples
    for (int j = 0; j < 12 && depth > 0.25 + 0.5 * j; ++j) {
      const double top = 0.25 + 0.5 * j, dz = std::min(depth, top + 0.5) - top, frac = dz / 0.5;
      w -= 2.0 * dz * (at(j) + 0.5 * frac * (at(j + 1) - at(j)));
    }
    return w;
  };
}

// The planned path positions of both cycles plus every ds mm over [a, b] of the last one (the
// transient's peak sampled densely: docs/segment.md "The driver exit's peel transient").
std::vector<double> dense_positions(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                                    const scene::SegmentLifeSetup& setup, const std::array<double, 3>& dense) {
  const belt::LoadHistory h(cycle, drive.belt, setup.temperature_C);
  const double L = h.length_mm(), half = segment::build_mesh(setup.section, setup.mesh).half_length_mm;
  const segment::CycleStepping& stepping = setup.cycle.stepping;
  std::vector<double> s;
  for (int c = 0; c < stepping.cycles; ++c)
    for (double b : segment::cycle_breakpoints(h, stepping.steps_per_cycle, stepping.change_weight, half))
      s.push_back((c + b) * L);
  for (double x = dense[0]; x <= dense[1] + 1e-9; x += dense[2]) s.push_back((stepping.cycles - 1) * L + x);
  std::sort(s.begin(), s.end());
  std::vector<double> out;
  for (double x : s)
    if (out.empty() || x > out.back() + 1e-6) out.push_back(x);
  return out;
}

struct Outcome {
  scene::SegmentLife life;
  double wall_s = 0.0;
  double main_cpu_s = 0.0;  // the calling thread's CPU time: the run's wall time on an idle machine, nearly
  segment::MeshKnobs mesh{};
  segment::Integration integration{};
};

// CPU time of the calling thread (s). With the element loop on helper threads, this is the run's
// critical path: its wall time on an otherwise idle machine, up to the waits for the helpers.
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// "iso": the bare drive file (Report I's E 20/8 MPa, ν 0.49 are set by run_probe); else the cards.
scene::Scene probe_scene(const Probe& pr) {
  return pr.fidelity == "iso" ? scene::load_scene(drive_file(pr.load))
                              : reference(pr.load);
}

Outcome run_probe(const Probe& pr) {
  const scene::Scene s = probe_scene(pr);
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const belt::LoadCycle cycle = belt::compute_load_cycle(drive);
  for (const belt::LoadSample& q : cycle.samples)  // loads=A:B: where the friction is used (the stick's limit)
    if (pr.loads[1] > pr.loads[0] && q.s_mm >= pr.loads[0] && q.s_mm <= pr.loads[1])
      std::printf("load s %.2f mm zone %s p %.4g MPa gamma %.1f deg slide %.4g mm/s friction used %.4g of %.4g\n", q.s_mm,
                  belt::to_string(q.zone), q.p_MPa, q.gamma_rad * 180.0 / M_PI, q.slide_mm_s, q.friction_used, drive.friction);
  scene::SegmentLifeSetup setup;
  setup.section = scene::cog_section(s);
  if (pr.fillet_mm >= 0.0) setup.section.root_fillet_mm = pr.fillet_mm;
  if (pr.tip_mm >= 0.0) setup.section.tip_radius_mm = pr.tip_mm;
  setup.mesh = mesh_named(pr.mesh);
  if (pr.rows > 0) setup.mesh.cushion_rows = pr.rows;
  if (pr.fine_mm > 0.0) setup.mesh.fine_size_mm = pr.fine_mm;
  if (pr.central > 0.0) setup.mesh.central_pitches = pr.central;
  if (pr.ends > 0.0) setup.mesh.end_pitches = pr.ends;
  if (pr.coarse_mm > 0.0) setup.mesh.coarse_size_mm = pr.coarse_mm;
  if (pr.gap_mm >= 0.0) setup.mesh.gap_size_mm = pr.gap_mm;
  if (pr.column_growth > 0.0) setup.mesh.column_growth = pr.column_growth;
  if (pr.row_growth > 0.0) setup.mesh.row_growth = pr.row_growth;
  if (!pr.vtk.empty()) segment::write_vtk(segment::build_mesh(setup.section, setup.mesh), pr.vtk);
  const double gap_depth = setup.section.height_mm - setup.section.cog_depth_mm;
  for (double d : {0.05, 0.1, 0.2, 0.3, 0.5, 0.75, 1.0})
    if (pr.land) setup.extra_points.push_back({"land-" + std::to_string(d).substr(0, 4), 0.0, d - gap_depth});
  for (int k = 1; k < 10 && pr.profile; ++k)
    setup.extra_points.push_back({"cushion-" + std::to_string(k), 0.0, -0.1 * k * setup.section.cushion_mm});
  for (int k = 0; pr.section_x >= 0.0 && k < 13; ++k)
    for (double sign : {-1.0, 1.0})
      setup.extra_points.push_back({(sign < 0 ? "left-" : "right-") + std::to_string(k), sign * pr.section_x,
                                    -0.25 - 0.5 * k});
  if (!pr.oracle.empty())
    setup.cycle.physics.end_shear_MPa = oracle_end(pr.oracle, 0), setup.cycle.physics.end_warping_mm = oracle_end(pr.oracle, 1);
  if (pr.end_condition == "free") setup.cycle.physics.ends = segment::EndCondition::free;
  if (pr.end_condition == "sheared") setup.cycle.physics.ends = segment::EndCondition::sheared;
  if (pr.end_condition == "radial") setup.cycle.physics.ends = segment::EndCondition::radial;
  setup.solver.newton.reuse_tangent = pr.reuse;
  if (pr.keep_below >= 0.0) setup.solver.newton.keep_preconditioner_below = pr.keep_below;
  if (pr.split >= 0) setup.solver.newton.split_factorisation = pr.split != 0;
  setup.solver.stepping.extrapolate_start = pr.extrapolate;
  if (!pr.integration.empty()) setup.solver.physics.integration = segment::integration_from_string(pr.integration);
  if (pr.stall >= 0) setup.solver.newton.stall_iterations = pr.stall;
  if (pr.growth >= 0) setup.solver.stepping.growth_iterations = pr.growth;
  setup.solver.stepping.max_cuts = pr.cuts;
  setup.solver.newton.levenberg = pr.levenberg;
  setup.solver.newton.tolerance = pr.tolerance;
  setup.solver.diagnose_failure = pr.diagnose;
  setup.solver.physics.inertia = pr.inertia;
  setup.cycle.stepping.cycles = pr.cycles;
  setup.cycle.outputs.vtk_prefix = pr.field_prefix, setup.cycle.outputs.vtk_at_s_mm = pr.field_at_mm;
  setup.solver.threads = pr.threads;
  if (pr.krylov >= 0) setup.solver.newton.krylov_iterations = pr.krylov;
  if (pr.plain_pressure) setup.solver.newton.linearised_pressure = false;
  if (pr.linear_predictor) setup.solver.stepping.rotated_predictor = false;
  if (pr.krylov_tolerance > 0.0) setup.solver.newton.krylov_tolerance = pr.krylov_tolerance;
  setup.cycle.stepping.steps_per_cycle = pr.steps;
  if (pr.first_steps >= 0) setup.cycle.stepping.conditioning_steps = pr.first_steps;
  if (pr.flank >= 0.0) setup.cycle.physics.flank_stiffness_N_mm4 = pr.flank;
  if (pr.tflank >= 0.0) setup.cycle.physics.flank_stick_N_mm4 = pr.tflank;
  if (pr.vflank >= 0.0) setup.cycle.physics.flank_slide_floor_mm_s = pr.vflank;
  if (pr.turn >= 0.0) setup.cycle.physics.flank_turn_N_mm4 = pr.turn;
  setup.solver.stepping.branch_switch = pr.branch;
  if (pr.body_sampling_mm >= 0.0) setup.cycle.physics.body_force_sampling_mm = pr.body_sampling_mm;
  setup.cycle.physics.manufactured_radius_mm = drive.geometry.belt_length_mm / (2.0 * M_PI);
  segment::RoleMaterialOptions o;
  o.fidelity = pr.fidelity == "complete" ? core::Fidelity::complete : core::Fidelity::elastic;
  o.temperature_C = s.temperature_C;
  o.frequency_Hz = drive.belt_speed_mm_s / drive.geometry.belt_length_mm;
  if (pr.lagged) o.damage_update = model::PointOptions::DamageUpdate::lagged;
  for (int k = 0; k < 2 && pr.fidelity == "iso"; ++k)  // Report I's exploratory isotropic runs
    setup.materials[k] = model::make_material_point(*model::make_model("elastic-iso", nlohmann::json::object()),
                                                    {k == 0 ? 20.0 : 8.0, 0.49});
  for (int k = 0; k < 2 && pr.fidelity != "iso"; ++k) {
    const card::Card c = card::load_card(s.materials.at(k == 0 ? "bottom" : "cushion"));
    std::vector<double> values = c.values();
    for (const auto& [name, value] : pr.overrides)
      for (std::size_t i = 0; i < values.size(); ++i)
        if (c.model()->parameters()[i].name == name) values[i] = value;
    o.damage_driver_hold = pr.hold ? card::DataWindow(windowed_card(k == 0 ? "material-1" : "material-2")).damage_drivers()
                                   : std::vector<double>{};
    setup.materials[k] = segment::role_point(*c.model(), values, o);
  }
  setup.temperature_C = s.temperature_C;
  if (pr.dense[2] > 0.0) setup.cycle.stepping.positions_mm = dense_positions(cycle, drive, setup, pr.dense);
  const core::Stopwatch watch;
  const double cpu0 = thread_cpu_s();
  Outcome out{scene::segment_life(cycle, drive, setup, fatigue::default_card()), 0.0};
  out.wall_s = watch.seconds();
  out.main_cpu_s = thread_cpu_s() - cpu0;
  out.mesh = setup.mesh, out.integration = setup.solver.physics.integration;
  return out;
}

void print_probe(const Probe& p, const Outcome& o) {
  const auto& r = o.life.run;
  const auto& m = o.life.report.modes;
  std::printf("| %s | %s | %s | %d | %d | %d | %d | %d | %d | %d | %.4g | %.4g | %s | %d | %.2f s |\n", p.load.c_str(),
              p.fidelity.c_str(), p.mesh.c_str(), r.elements, p.steps, r.increments, r.newton_iterations,
              r.factorizations, r.final_state.assemblies, r.cuts, m[0].life_cycles, m[1].life_cycles, o.life.report.governing.c_str(),
              r.final_state.threads, o.wall_s);
}

// Each cushion point of a probe (and each `land` point): its straight-section position (from the wrapped reference, mould
// radius L/2π), its peak |σ11|, |σ12| over the last cycle and the
// life of that point alone (docs/segment.md §"Mode 2 through the cushion").
void print_cushion_points(const Probe& pr, const Outcome& o) {
  const scene::Scene s = probe_scene(pr);
  const belt::DriveCase drive = scene::make_drive(s, scene::resolve_stiffness(s));
  const fatigue::LifeConditions conditions =
      scene::segment_conditions(belt::compute_load_cycle(drive), drive, s.temperature_C, o.life.run);
  const double R = drive.geometry.belt_length_mm / (2.0 * M_PI);
  const auto histories = scene::segment_point_histories(o.life.run);
  std::printf("cushion / land point | (x, depth) mm | max |s11| | max |s12| MPa | N2 / N1 of the point\n");
  for (std::size_t k = 0; k < histories.size(); ++k) {
    if (histories[k].role != fatigue::Role::cushion && histories[k].name.rfind("land-", 0) != 0) continue;
    const segment::MonitoredHistory& mh = o.life.run.points[k];
    const Eigen::Vector2d X = mh.X_mm;
    const double depth = R - std::hypot(X.x(), X.y() + R), x = R * std::atan2(X.x(), X.y() + R);
    double s11 = 0.0, s12 = 0.0;
    for (const auto& q : histories[k].samples)
      if (q.t_s > histories[k].samples.back().t_s - o.life.run.cycle_time_s)
        s11 = std::max(s11, std::abs(q.s11_MPa)), s12 = std::max(s12, std::abs(q.s12_MPa));
    const auto one = fatigue::evaluate_life({histories[k]}, fatigue::default_card(), conditions);
    std::printf("%s | (%.4f, %.4f) | %.4f | %.4f | %.4g (%zu peaks)\n", histories[k].name.c_str(), x, depth, s11, s12,
                one.modes[0].life_cycles, one.modes[0].peaks.size());
  }
}

const char* kProbeHeader =
    "| drive | fidelity | mesh | elements | steps/cycle | increments | iterations | factorisations | assemblies | cuts "
    "| N1 | N2 | governing | threads | time |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";

double effect_s(const scene::SceneResult& r, const std::string& name) {
  for (const auto& e : r.plan.effects)
    if (e.name == name) return e.wall_s;
  return 0.0;
}

// The beam level's time per drive on the idle machine of 2026-11-25 (docs/fatigue.md "Measured"),
// where the segment levels' targets (elastic <= 1 s, complete <= 5 s) were met: this run's times
// scaled by the beam level's ratio say what they would be on that machine (the machine's speed
// varies 1.5-2x from day to day; the beam level did not change since).
double reference_beam_s(const std::string& load) {
  return load == "light" ? 0.74e-3 : load == "medium" ? 0.77e-3 : load == "heavy" ? 0.80e-3 : 0.0;
}

void level_table(const std::vector<const char*>& levels) {
  std::printf("## 1. Life per fidelity level (scene run = fitcli life's route, 2 load cycles; the segment's "
              "element loop on %d threads)\n\n", segment::solver_threads(segment::SolverKnobs{}));
  std::printf("'at 11-25 speed': the scene run x (the beam run on 2026-11-25's idle machine / this run's beam run)"
              ", the figure the targets (elastic <= 1 s, complete <= 5 s) are read against\n\n");
  std::printf("| drive | fidelity | N1 radial crack | N2 separation | governing | life (h) | scene run | "
              "stresses | vs beam | at 11-25 speed |\n|---|---|---|---|---|---|---|---|---|---|\n");
  for (const char* load : kLoads) {
    double beam_s = 0.0;
    for (const char* level : levels) {
      const scene::Scene s = life_scene(load, level);
      const core::Stopwatch watch;
      scene::SceneResult r;
      try {
        r = scene::run_scene(s);
      } catch (const std::exception& e) {
        std::printf("| %s | %s | refused: %.90s… |\n", load, level, e.what());
        continue;
      }
      double t_run = watch.seconds();
      if (std::strcmp(level, "beam") == 0) t_run = beam_s = core::seconds_per_call([&] { scene::run_scene(s); });
      const auto& m = r.life->report.modes;
      std::printf("| %s | %s | %.4g | %.4g | %s | %.4g | %.4g s | %.4g s | %.3g | %.3g s |\n", load, level,
                  m[0].life_cycles, m[1].life_cycles, r.life->report.governing.c_str(), r.life->report.life_h, t_run,
                  effect_s(r, std::strcmp(level, "beam") == 0 ? "beam_stresses" : "segment_fe"), t_run / beam_s,
                  t_run * reference_beam_s(load) / beam_s);
      std::fflush(stdout);
    }
  }
}

// Least-squares slope of log t against log x.
double exponent(const std::vector<double>& x, const std::vector<double>& t) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double a = std::log(x[k]), b = std::log(t[k]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void convergence(const std::string& fidelity) {
  std::printf("\n## 2–3. Convergence and cost, medium drive, %s\n\n%s", fidelity.c_str(), kProbeHeader);
  std::vector<double> elements, t_mesh, steps, t_steps;
  std::vector<Outcome> by_mesh, by_steps, by_length;
  for (const char* mesh : {"coarse", "medium"}) {
    const Probe p{"medium", fidelity, mesh, 60, false};
    by_mesh.push_back(run_probe(p));
    print_probe(p, by_mesh.back());
    elements.push_back(by_mesh.back().life.run.elements), t_mesh.push_back(by_mesh.back().wall_s);
  }
  by_length.push_back(by_mesh[0]);
  Probe radial{"medium", fidelity, "coarse", 60, false};  // the life mesh with the former radial ends
  radial.end_condition = "radial";
  by_length.push_back(run_probe(radial));
  print_probe(radial, by_length.back());
  for (const char* mesh : {"long", "longer"}) {  // the segment's length: 27, 54, 81 mm
    const Probe p{"medium", fidelity, mesh, 60, false};
    by_length.push_back(run_probe(p));
    print_probe(p, by_length.back());
  }
  for (int n : {20, 40, 80}) {
    const Probe p{"medium", fidelity, "coarse", n, false};
    by_steps.push_back(run_probe(p));
    print_probe(p, by_steps.back());
    steps.push_back(n), t_steps.push_back(by_steps.back().wall_s);
  }
  auto change = [](const Outcome& a, const Outcome& ref, int mode) {
    return 100.0 * (a.life.report.modes[mode].life_cycles / ref.life.report.modes[mode].life_cycles - 1.0);
  };
  std::printf("\nlife change against the finer (%%): mesh coarse vs medium N1 %+.1f N2 %+.1f; steps 20 vs 80 "
              "N1 %+.1f N2 %+.1f, 40 vs 80 N1 %+.1f N2 %+.1f\n",
              change(by_mesh[0], by_mesh[1], 0), change(by_mesh[0], by_mesh[1], 1), change(by_steps[0], by_steps[2], 0),
              change(by_steps[0], by_steps[2], 1), change(by_steps[1], by_steps[2], 0), change(by_steps[1], by_steps[2], 1));
  std::printf("segment length (27 mm sheared / 27 mm radial / 54 mm against 81 mm): N1 %+.1f / %+.1f / %+.1f, "
              "N2 %+.1f / %+.1f / %+.1f\n",
              change(by_length[0], by_length[3], 0), change(by_length[1], by_length[3], 0),
              change(by_length[2], by_length[3], 0), change(by_length[0], by_length[3], 1),
              change(by_length[1], by_length[3], 1), change(by_length[2], by_length[3], 1));
  std::printf("scaling: time ~ elements^%.2f, time ~ steps^%.2f\n", exponent(elements, t_mesh), exponent(steps, t_steps));
  std::fflush(stdout);
}

// The complete level's lives on the light drive against mesh and steps (docs/segment.md "Which
// segment N1 should be read from"); points read as the mean over the elements that share them.
void complete_convergence() {
  std::printf("\n## 5. Complete level, light drive: convergence in mesh and steps (2 cycles)\n\n%s", kProbeHeader);
  struct Row {
    const char* label;
    const char* mesh;
    int steps;
    int rows;
    double fine, coarse;
  };
  const Row rows[] = {
      {"life mesh (1 cushion row, graded)", "life", 120, 0, 0.0, 0.0},
      {"the same, 240 steps", "life", 240, 0, 0.0, 0.0},
      {"1 mm graded, 3 cushion rows", "life", 120, 3, 0.0, 0.0},
      {"0.5 mm graded, 1 cushion row", "coarse", 120, 0, 0.5, 0.0},
      {"0.6 mm graded, 3 rows", "coarse", 120, 3, 0.6, 0.0},
      {"0.35 mm graded, 3 rows", "coarse", 120, 3, 0.35, 0.0},
      {"reference: 0.25 mm, 1.25 mm ends, graded, 3 rows", "coarse", 120, 3, 0.25, 1.25},
  };
  std::vector<std::pair<const Row*, Outcome>> out;
  for (const Row& row : rows) {
    Probe p{"light", "complete", row.mesh, row.steps};
    p.rows = row.rows, p.fine_mm = row.fine, p.coarse_mm = row.coarse;
    try {
      out.emplace_back(&row, run_probe(p));
      print_probe(p, out.back().second);
    } catch (const std::exception& e) {
      std::printf("| light | complete | %s | failed: %.120s |\n", row.label, e.what());
    }
    std::fflush(stdout);
  }
  if (out.empty() || std::string(out.back().first->label).rfind("reference", 0) != 0) return;
  const Outcome& ref = out.back().second;
  std::printf("\n| mesh | steps | N1 / reference | N2 / reference | governing | time / the first row's |\n"
              "|---|---|---|---|---|---|\n");
  for (const auto& [row, o] : out)
    std::printf("| %s | %d | %.3g | %.3g | %s | %.2f |\n", row->label, row->steps,
                o.life.report.modes[0].life_cycles / ref.life.report.modes[0].life_cycles,
                o.life.report.modes[1].life_cycles / ref.life.report.modes[1].life_cycles,
                o.life.report.governing.c_str(), o.wall_s / out.front().second.wall_s);
  std::fflush(stdout);
}

void beam_sweep() {
  std::printf("\n## 4. Beam level: sweep of 1000 drives through the planner\n\n");
  scene::Scene s = life_scene("medium", "beam");
  const SweepCounts c = sweep_1000_drives(s, [](const scene::Scene& d) {
    return scene::run_scene(d).life->report.governing;
  });
  std::printf("1000 drives in %.3f s (%.3f ms per drive): %d computed, %d refused (belt slips), "
              "%d governed by separation\n", c.seconds, c.seconds, c.done, c.refused, c.separation);
}

}  // namespace

// A fatigue card with Report I's constants and a made-up scatter (s 0.3) and covariance, for the
// distribution's cost (docs/fatigue.md §9).
std::string scatter_card_file() {
  fatigue::FatigueCard c = fatigue::default_card();
  for (fatigue::Mode m : {fatigue::Mode::radial_crack, fatigue::Mode::separation}) {
    c.law(m).scatter = fatigue::LifeScatter{"lognormal", 0.3, 8};
    fatigue::LawCovariance cov{};
    cov[0][0] = 4e-4, cov[1][1] = 0.25, cov[2][2] = 1e-4;
    c.law(m).covariance = cov;
  }
  const std::string path = "/tmp/fitlib-bench-life-" + std::to_string(::getpid()) + "-scatter.json";
  fatigue::save_card(path, c);
  return path;
}

// Wall time of the scene's life, best of `runs`.
double best_life_s(const scene::Scene& s, int runs, scene::SceneResult& out) {
  double best = HUGE_VAL;
  for (int k = 0; k < runs; ++k) {
    const core::Stopwatch w;
    out = scene::run_life(s);
    best = std::min(best, w.seconds());
  }
  return best;
}

// 6. What heat build-up ([effects] heat_buildup, ambient 25 degC) and the life distribution (a card
// with scatter and covariance) cost per drive against the run without them (docs/thermal.md).
void heat_table() {
  std::printf("## 6. Heat build-up and the life distribution: cost per drive (thesis cards, ambient 25 degC)\n\n"
              "| drive | level | without | heat build-up | ratio | iterations | belt temperature | heat in (hyst. + friction share) | "
              "life at 80 degC -> at the belt temperature | with distribution | ratio | B10 (governing) |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const std::string card = scatter_card_file();
  for (const char* load : kLoads)
    for (const char* level : {"beam", "elastic"}) {
      scene::Scene s = life_scene(load, level);
      const int runs = std::string(level) == "beam" ? 20 : 1;
      try {
        scene::SceneResult off, on, dist;
        const double t_off = best_life_s(s, runs, off);
        scene::Scene h = s;
        h.effects["heat_buildup"] = true, h.ambient_C = 25.0, h.thermal.ambient_C = 25.0;
        const double t_on = best_life_s(h, runs, on);
        scene::Scene d = s;
        d.life->card = card;
        const double t_dist = best_life_s(d, runs, dist);
        const auto& q = *on.heat;
        std::string b10 = "-";
        for (const auto& m : dist.life->distribution)
          if (fatigue::to_string(m.mode) == dist.life->report.governing) b10 = core::short_number(m.b10.h) + " h";
        std::printf("| %s | %s | %.3g s | %.3g s | %.2f | %d | %.2f degC | %.3g W (%.3g + %.3g x %.3g) | %.4g -> %.4g h | %.3g s | %.2f | %s |\n",
                    load, level, t_off, t_on, t_on / t_off, q.iterations, q.temperature_C, q.heat_in_W,
                    q.sources.hysteresis_W, q.paths.friction_to_belt, q.sources.friction_W, off.life->report.life_h,
                    on.life->report.life_h, t_dist, t_dist / t_off, b10.c_str());
      } catch (const core::InputError& e) {
        std::printf("| %s | %s | refused: %s |\n", load, level, e.what());
      }
    }
  std::remove(card.c_str());
  std::printf("\n");
}

// 7. What [life] uncertainty = "cards" and "constants+cards" cost per drive against the run without them (docs/thermal.md
// §7): the thesis cards, the bottom card given a covariance of its mean moduli (variance 4e-3 in
// ln, correlation 0.5; the bundled cards are true values without one), the scatter card of table 6,
// the default 100 draws at the beam level, 8 at the elastic level on the light drive
// (`bench_life uncertainty` prints it alone).
std::string covariance_card_file() {
  card::Card c = card::load_card(kRoot + "/datasets/cards/material-1-true.json");
  const double v = 4e-3, r = 0.5 * v;
  c.fit["covariance"] = {{"parameters", {"G_Im", "C33_Am", "C44_Am"}},
                         {"coordinates", {"ln", "ln", "ln"}},
                         {"matrix", {{v, r, r}, {r, v, r}, {r, r, v}}}};
  const std::string path = "/tmp/fitlib-bench-life-" + std::to_string(::getpid()) + "-covariance.json";
  card::save_card(path, c);
  return path;
}

void uncertainty_table() {
  std::printf("## 7. [life] uncertainty = \"cards\" and \"constants+cards\": cost per drive (thesis cards, bottom card with a "
              "covariance)\n\n"
              "| drive | level | draws | without | cards | ratio | per draw / run without | constants+cards | ratio | "
              "per draw | per draw / run without | B10 (governing) | constants' 90 %% | cards' 90 %% | combined 90 %% |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  const std::string scatter = scatter_card_file(), bottom = covariance_card_file();
  for (const char* load : kLoads)
    for (const char* level : {"beam", "elastic"}) {
      const bool beam = std::string(level) == "beam";
      if (!beam && std::string(load) != "light") continue;
      scene::Scene s = life_scene(load, level);
      s.materials["bottom"] = bottom;
      s.life->card = scatter;
      try {
        scene::SceneResult off, on, both;
        const double t_off = best_life_s(s, beam ? 20 : 1, off);
        s.life->uncertainty_cards = true;
        s.life->samples = beam ? 100 : 8;
        const double t_on = best_life_s(s, beam ? 3 : 1, on);
        s.life->uncertainty_combined = true;  // "constants+cards": the same draws and the combined interval
        const double t_both = best_life_s(s, beam ? 3 : 1, both);
        std::string b10 = "-", constants = "-", cards = "-", combined = "-";
        auto range = [](double lo, double hi) { return "[" + core::short_number(lo) + ", " + core::short_number(hi) + "]"; };
        for (const auto& m : both.life->distribution)
          if (fatigue::to_string(m.mode) == both.life->report.governing) {
            b10 = core::short_number(m.b10.h) + " h";
            constants = range(m.b10.low_h, m.b10.high_h);
            cards = range(m.b10.cards_low_h, m.b10.cards_high_h);
            combined = range(m.b10.combined_low_h, m.b10.combined_high_h);
          }
        const double n = s.life->samples;
        std::printf("| %s | %s | %d | %.3g s | %.3g s | %.1f | %.2f | %.3g s | %.1f | %.3g ms | %.2f | %s | %s | %s | %s |\n",
                    load, level, s.life->samples, t_off, t_on, t_on / t_off, t_on / t_off / n, t_both, t_both / t_off,
                    1e3 * t_both / n, t_both / t_off / n, b10.c_str(), constants.c_str(), cards.c_str(),
                    combined.c_str());
      } catch (const std::runtime_error& e) {  // refused (exit 3) or stopped (exit 4)
        std::printf("| %s | %s | stopped: %s |\n", load, level, e.what());
      }
    }
  std::remove(scatter.c_str());
  std::remove(bottom.c_str());
  std::printf("\n");
}

// 11. The heat source per level against the complete level's own dissipation (docs/thermal.md §1,
// docs/decisions.md "Heat: the beam and elastic levels' cushion shear"): every drive that passes the
// complete level with the cards' damage held (the level calibration's, scripts/calibrate-levels.sh),
// the windowed thesis cards at every level, each drive's own temperature. Per drive: the segment's
// dissipation per role (the complete level), the beam section's layers (the beam and elastic levels'
// source) and their ratio; with `temperatures`, the belt temperature with heat build-up (ambient
// 25 degC) at the beam level (the elastic level reads the same layers: the same temperature) and at
// the complete level (`bench_life heatlevels [temperatures]` prints it alone).
const char* kHeatDrives[] = {"light", "medium", "heavy", "acc-0500-pulley-120.toml", "acc-0500-slack-300.toml",
                             "acc-0500-tension-700.toml", "acc-0500-torque-15.toml"};

scene::Scene heat_scene(const std::string& load, const std::string& level) {
  scene::Scene s = life_scene(load, "complete held");  // the windowed cards
  s.life->fidelity = core::fidelity_from_string(level, "level");
  return s;
}

// Half the range of σ12 over the last `period_s` of the history, the largest over the `role` points.
double shear_half_range(const std::vector<fatigue::PointHistory>& points, fatigue::Role role, double period_s) {
  double best = 0.0;
  for (const fatigue::PointHistory& p : points) {
    if (p.role != role || p.samples.empty()) continue;
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (const fatigue::StressSample& q : p.samples)
      if (q.t_s >= p.samples.back().t_s - period_s - 1e-12) lo = std::min(lo, q.s12_MPa), hi = std::max(hi, q.s12_MPa);
    if (hi > lo) best = std::max(best, 0.5 * (hi - lo));
  }
  return best;
}

// √2 × the rms of σ12 about its mean over the last `period_s` of the history (trapezoidal in time):
// the amplitude of the sinusoid that dissipates what the history does in a linear viscoelastic
// solid of frequency-flat G″ (Parseval); the largest over the `role` points.
double shear_rms_amplitude(const std::vector<fatigue::PointHistory>& points, fatigue::Role role, double period_s) {
  double best = 0.0;
  for (const fatigue::PointHistory& p : points) {
    if (p.role != role || p.samples.size() < 2) continue;
    const double t0 = p.samples.back().t_s - period_s;
    double T = 0.0, m = 0.0, m2 = 0.0;
    for (std::size_t k = 1; k < p.samples.size(); ++k) {
      const auto &a = p.samples[k - 1], &b = p.samples[k];
      if (a.t_s < t0 - 1e-12) continue;
      const double dt = b.t_s - a.t_s;
      T += dt, m += 0.5 * dt * (a.s12_MPa + b.s12_MPa), m2 += 0.5 * dt * (a.s12_MPa * a.s12_MPa + b.s12_MPa * b.s12_MPa);
    }
    if (T > 0.0) best = std::max(best, std::sqrt(2.0 * std::max(0.0, m2 / T - (m / T) * (m / T))));
  }
  return best;
}

// The cushion card's shear |G*| and G″ at the scene's temperature and load frequency, amplitude `gamma`.
std::array<double, 2> cushion_shear(const scene::Scene& s, const belt::DriveCase& drive, double gamma) {
  const card::Card c = card::load_card(s.materials.at("cushion"));
  model::TestCondition at;
  at.temperature_C = s.temperature_C, at.frequency_Hz = drive.belt_speed_mm_s / drive.geometry.belt_length_mm;
  at.mode = model::TestMode::shear, at.strain_amplitude = gamma;
  const auto m = card::moduli_in_mode(*c.model(), c.values(), at, s.material_poisson_ratio);
  return {std::hypot(m.storage, m.loss), m.loss};
}

void heat_level_table(bool temperatures) {
  std::printf("## 11. The heat source per level against the complete level's dissipation (windowed thesis cards, "
              "the drive's temperature)\n\n"
              "| drive | T | complete: bottom / cushion | beam and elastic layers: bottom (stretch + shear) / cushion "
              "(stretch + shear) | cushion shear gamma_a | layers / complete: bottom, cushion, total |%s\n"
              "|---|---|---|---|---|---|%s\n",
              temperatures ? " belt temperature (heat build-up, 25 degC): beam and elastic / complete (runs) |" : "",
              temperatures ? "---|" : "");
  std::string notes;  // the cushion's shear per drive, below the table
  for (const char* load : kHeatDrives) {
    const scene::Scene s = heat_scene(load, "complete");
    try {
      const scene::SceneResult r = scene::run_life(s);
      const belt::HeatSources h = scene::heat_sources_of_run(s, r);
      const double f = r.drive->belt_speed_mm_s / r.drive->geometry.belt_length_mm;  // one cycle per revolution
      // The layers' W by name: bottom stretch (land, cogs), bottom shear (land, cogs), cushion stretch, shear.
      auto layer = [&](const std::string& name) -> const belt::HysteresisLayer& {
        for (const auto& l : h.layers)
          if (l.name == name) return l;
        throw std::logic_error("no heat layer " + name);
      };
      const char* names[6] = {"bottom rubber, land", "bottom rubber, cogs", "bottom rubber, land shear",
                              "bottom rubber, cogs shear", "cushion, stretch", "cushion, shear"};
      double W[6];
      for (int k = 0; k < 6; ++k) W[k] = belt::hysteresis_work_J(layer(names[k])) * f;
      const double layer_W[4] = {W[0] + W[1], W[2] + W[3], W[4], W[5]};  // stretch, shear of the bottom; the cushion's
      const double bottom = layer_W[0] + layer_W[1], cushion = layer_W[2] + layer_W[3];
      const auto& c = r.segment_hysteresis_roles_W;
      // The cushion's shear: τ_a of the beam's mid-cushion point (B_l h) and of the complete level's
      // cushion points; the γ_a whose π G″ γ_a² (G″ at that γ_a) makes the complete level's cushion
      // dissipation less the stretch layer's; the card's |G*| at the layer's γ_a and at its tests' largest.
      const fatigue::BeamSection sec = fatigue::default_beam_section(*r.drive, s.temperature_C);
      const double tau_beam = shear_half_range(fatigue::beam_stress_histories(*r.cycle, *r.drive, sec), fatigue::Role::cushion, 1.0 / f);
      const double tau_complete = shear_half_range(*r.stresses, fatigue::Role::cushion, 1.0 / f);
      const belt::HysteresisLayer& shear = layer("cushion, shear");
      const double target_J = (c[1] - layer_W[2]) / f * 1e3;  // N mm per cycle
      double gamma_needed = NAN;
      if (target_J > 0.0) {
        double g = shear.strain_amplitude;
        for (int it = 0; it < 50; ++it) g = std::sqrt(target_J / (M_PI * cushion_shear(s, *r.drive, g)[1] * shear.volume_mm3));
        gamma_needed = g;
      }
      const card::DataWindow window(card::load_card(s.materials.at("cushion")));
      const double tested = window.strain_amplitude_range() ? window.strain_amplitude_range()->second : NAN;
      const double G_layer = cushion_shear(s, *r.drive, shear.strain_amplitude)[0];
      const double G_tested = cushion_shear(s, *r.drive, tested)[0];
      const double period = 1.0 / f;
      const double rms_beam = shear_rms_amplitude(fatigue::beam_stress_histories(*r.cycle, *r.drive, sec), fatigue::Role::cushion, period);
      const double rms_complete = shear_rms_amplitude(*r.stresses, fatigue::Role::cushion, period);
      char rms_line[300];
      std::snprintf(rms_line, sizeof rms_line, "  rms amplitude sqrt(2 var) of tau: beam %.4g, complete %.4g; rms_beam/|G*| tested %.4g\n",
                    rms_beam, rms_complete, rms_beam / G_tested);
      char line[600];
      std::snprintf(line, sizeof line, "- %s: tau_a beam %.4g, complete %.4g (ratio %.3f) MPa; gamma_a layer %.4g (|G*| %.4g MPa), needed %.4g "
                  "(|G*| %.4g); tests' largest %.4g (|G*| %.4g, tau_beam/|G*| %.4g, tau_complete/|G*| %.4g)\n",
                  load, tau_beam, tau_complete, tau_complete / tau_beam, shear.strain_amplitude, G_layer, gamma_needed,
                  std::isnan(gamma_needed) ? NAN : cushion_shear(s, *r.drive, gamma_needed)[0], tested, G_tested,
                  tau_beam / G_tested, tau_complete / G_tested);
      notes += line;
      notes += rms_line;
      std::string temps;
      if (temperatures) {
        auto belt_T = [&](const std::string& level, std::string* runs) {
          scene::Scene t = heat_scene(load, level);
          t.effects["heat_buildup"] = true, t.ambient_C = 25.0, t.thermal.ambient_C = 25.0;
          try {
            const scene::SceneResult q = scene::run_life(t);
            if (runs) *runs = std::to_string(q.heat->segment_runs);
            return core::short_number(q.heat->temperature_C) + " degC";
          } catch (const std::runtime_error& e) {
            return std::string("stopped: ") + e.what();
          }
        };
        std::string runs = "-";
        const std::string beam = belt_T("beam", nullptr), complete = belt_T("complete", &runs);
        temps = " " + beam + " / " + complete + " (" + runs + ") |";
      }
      std::printf("| %s | %.0f degC | %.3g / %.3g W | %.3g (%.3g + %.3g) / %.3g (%.3g + %.3g) W | %.3g | %.2f, %.2f, %.2f |%s\n",
                  load, s.temperature_C, c[0], c[1], bottom, layer_W[0], layer_W[1], cushion, layer_W[2], layer_W[3],
                  shear.strain_amplitude, bottom / c[0], cushion / c[1],
                  (bottom + cushion) / (c[0] + c[1]), temps.c_str());
    } catch (const std::runtime_error& e) {
      std::printf("| %s | stopped: %s |\n", load, e.what());
    }
    std::fflush(stdout);
  }
  std::printf("\nThe cushion's shear:\n%s\n", notes.c_str());
}

// 9. The design-point scan's cost ([segment] scan = true, docs/segment.md "Design points by scanning"):
// each reference drive at the elastic level and the complete level with the damage held, with and
// without the scan; the candidates it evaluates per mode and where the governing mode's design point
// lands (`bench_life scan` prints it alone).
scene::Scene scanning(const std::string& load, scene::Scene s) {
  const std::string path = "/tmp/fitlib-bench-life-" + std::to_string(::getpid()) + "-scan.toml";
  std::ofstream(path) << core::read_file(drive_file(load)) << "\n[segment]\nscan = true\n";
  s.segment = scene::load_scene(path).segment;  // the user's route: the drive's file with [segment] scan = true
  std::remove(path.c_str());
  return s;
}

std::string mode_lives(const fatigue::LifeReport& r) {
  std::string out;
  for (const fatigue::ModeLife& m : r.modes)
    out += (out.empty() ? "" : " / ") + core::short_number(m.life_cycles) + " (" +
           std::to_string(m.points_evaluated) + ")";
  return out;
}

void scan_table() {
  std::printf("## 9. The design-point scan: cost per drive ([segment] scan = true; 2 cycles)\n\n"
              "| drive | level | named points (wall) | with the scan (wall) | ratio (CPU ratio) | N1 / N2 named (points) | N1 / N2 scanned (points) | "
              "governing design point (scanned) |\n|---|---|---|---|---|---|---|---|\n");
  for (const char* load : {"light", "medium", "heavy"})
    for (const char* level : {"elastic", "complete held"}) {
      const scene::Scene s = life_scene(load, level);
      try {
        scene::SceneResult off, on;
        const std::clock_t c0 = std::clock();
        const double t_off = best_life_s(s, 1, off);
        const std::clock_t c1 = std::clock();
        const double t_on = best_life_s(scanning(load, s), 1, on);
        const double cpu_ratio = static_cast<double>(std::clock() - c1) / static_cast<double>(c1 - c0);
        std::string at = "-";
        for (const fatigue::ModeLife& m : on.life->report.modes)
          if (fatigue::to_string(m.mode) == on.life->report.governing)
            at = m.design_point + " (" + core::short_number(m.x_mm) + ", " + core::short_number(m.y_mm) + ") mm";
        std::printf("| %s | %s | %.3g s | %.3g s | %.2f (CPU %.2f) | %s | %s | %s |\n", load, level, t_off, t_on, t_on / t_off, cpu_ratio,
                    mode_lives(off.life->report).c_str(), mode_lives(on.life->report).c_str(), at.c_str());
      } catch (const std::runtime_error& e) {  // refused (exit 3) or stopped (exit 4)
        std::printf("| %s | %s | stopped: %s |\n", load, level, e.what());
      }
    }
  std::printf("\n");
}

// 10. The segment levels' cost per reference drive (docs/segment.md "Cost (reference)"): wall and
// CPU time (user + sys, every thread) of this build's `fitcli life` (next to bench_life) at the
// complete (damage held) and the elastic level, best of `runs`, against a baseline `fitcli` binary
// (e.g. main's before a change) on the same scene file, the two alternating; the largest relative
// difference of the modes' lives, whether life.json has the same bytes, and the sha256 of both
// runs' life.json and stress_history.csv (issue 32 item 6).
double cpu_s(int who) {
  rusage u{};
  ::getrusage(who, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The reference drive's scene `s` (life_scene: its cards and [life] fidelity and cycles), as a file
// a `fitcli` binary reads.
std::string reference_scene_file(const std::string& load, const scene::Scene& s) {
  std::ifstream in(drive_file(load));
  std::ostringstream text;
  for (std::string line; std::getline(in, line);) {
    text << line << "\n";
    if (line == "[belt]")
      text << "materials = { bottom = \"" << s.materials.at("bottom") << "\", cushion = \"" << s.materials.at("cushion")
           << "\" }\n";
  }
  const std::string level = core::to_string(s.life->fidelity.value_or(core::Fidelity::beam));
  text << "\n[life]\nfidelity = \"" << level << "\"\ncycles = " << s.life->cycles << "\n";
  const std::string path = "/tmp/fitlib-bench-life-" + std::to_string(::getpid()) + "-" + load + "-" + level + ".toml";
  std::ofstream(path) << text.str();
  return path;
}

struct ChildRun {
  double wall_s = HUGE_VAL, cpu_s = HUGE_VAL;
  std::string life_json;  // its bytes
  nlohmann::json life;
  std::string life_sha, history_sha;  // sha256 (first 16 hex digits) of life.json and stress_history.csv
};

// The first 16 hex digits of `path`'s sha256, "-" when it is absent.
std::string sha256_16(const std::string& path) {
  return std::filesystem::exists(path) ? core::sha256_hex(core::read_file(path)).substr(0, 16) : "-";
}

// `binary` life on `scene_file` into `out`: the best wall and CPU time so far, and its life.json.
void run_child(const std::string& binary, const std::string& scene_file, const std::string& out, ChildRun& run) {
  const std::string command = binary + " life -q --scene " + scene_file + " --out-dir " + out + " > /dev/null 2>&1";
  const double c0 = cpu_s(RUSAGE_CHILDREN);
  const core::Stopwatch w;
  const bool ok = std::system(command.c_str()) == 0;
  run.wall_s = std::min(run.wall_s, ok ? w.seconds() : NAN), run.cpu_s = std::min(run.cpu_s, cpu_s(RUSAGE_CHILDREN) - c0);
  const std::string life_file = out + "/life.json";
  run.life_json = std::filesystem::exists(life_file) ? core::read_file(life_file) : "";
  run.life = nlohmann::json::parse(run.life_json, nullptr, false);
  run.life_sha = run.life_json.empty() ? "-" : core::sha256_hex(run.life_json).substr(0, 16);
  run.history_sha = sha256_16(out + "/stress_history.csv");
}

void cost_table(const std::string& baseline, int runs) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "fitcli";
  std::printf("## 10. The segment levels' cost per reference drive (fitcli life, 2 cycles, best of %d; CPU = user + sys "
              "of every thread)\n\nthis build: %s; baseline: %s\n\n| drive | level | increments | iterations | wall | "
              "CPU | baseline wall | baseline CPU | wall ratio | CPU ratio | lives' largest relative difference | "
              "life.json | sha256 life.json, baseline → this | sha256 stress_history.csv, baseline → this |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n", runs, self.c_str(),
              baseline.empty() ? "none" : baseline.c_str());
  const std::string out = "/tmp/fitlib-bench-life-" + std::to_string(::getpid()) + "-out";
  for (const char* level : {"complete held", "elastic"})  // (the complete level passes every drive with the hold)
    for (const char* load : {"light", "medium", "heavy"}) {
      const std::string file = reference_scene_file(load, life_scene(load, level));
      ChildRun mine, theirs;
      for (int k = 0; k < runs; ++k) {  // alternating, so both see the same machine
        run_child(self, file, out + "-this", mine);
        if (!baseline.empty()) run_child(baseline, file, out + "-baseline", theirs);
      }
      double difference = baseline.empty() ? NAN : 0.0;
      for (std::size_t m = 0; !baseline.empty() && m < 2; ++m) {
        const auto life = [m](const ChildRun& r) { return r.life.is_discarded() ? double(NAN) : r.life["modes"][m].value("life_cycles", double(NAN)); };
        difference = std::max(difference, std::abs(life(mine) - life(theirs)) / std::abs(life(theirs)));
      }
      const auto count = [&](const char* key) { return mine.life.is_discarded() ? 0 : mine.life["segment_run"].value(key, 0); };
      std::printf("| %s | %s | %d | %d | %.3g s | %.3g s | %.3g s | %.3g s | %.2f | %.2f | %.2g | %s | %s → %s | %s → %s |\n",
                  load, level, count("increments"), count("newton_iterations"), mine.wall_s, mine.cpu_s, theirs.wall_s,
                  theirs.cpu_s, mine.wall_s / theirs.wall_s, mine.cpu_s / theirs.cpu_s, difference,
                  baseline.empty() ? "-" : mine.life_json == theirs.life_json ? "same bytes" : "differs",
                  theirs.life_sha.c_str(), mine.life_sha.c_str(), theirs.history_sha.c_str(), mine.history_sha.c_str());
      std::fflush(stdout);
      std::remove(file.c_str());
    }
  std::filesystem::remove_all(out + "-this");
  std::filesystem::remove_all(out + "-baseline");
  std::printf("\n");
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "cost") {  // table 10 only: bench_life cost [BASELINE_FITCLI] [runs=N]
    const BaselineArgs a = baseline_args(argc, argv, 3);
    cost_table(a.baseline, a.runs);
    return 0;
  }
  if (argc >= 6 && std::string(argv[1]) == "probe") {
    Probe p{argv[2], argv[3], argv[4], std::atoi(argv[5])};
    for (int k = 6; k < argc; ++k) {
      const std::string a = argv[k];
      if (a == "reuse") p.reuse = true;
      if (a.rfind("keep=", 0) == 0) p.keep_below = std::atof(a.c_str() + 5);
      if (a.rfind("split=", 0) == 0) p.split = std::atoi(a.c_str() + 6);
      if (a.rfind("first=", 0) == 0) p.first_steps = std::atoi(a.c_str() + 6);
      if (a == "extrapolate") p.extrapolate = true;
      if (a == "full" || a == "fbar" || a == "reduced") p.integration = a;
      if (a == "lagged") p.lagged = true;
      if (a.rfind("set=", 0) == 0 && a.find('=', 4) != std::string::npos)
        p.overrides.emplace_back(a.substr(4, a.find('=', 4) - 4), std::atof(a.c_str() + a.find('=', 4) + 1));
      if (a.rfind("stall=", 0) == 0) p.stall = std::atoi(a.c_str() + 6);
      if (a.rfind("cuts=", 0) == 0) p.cuts = std::atoi(a.c_str() + 5);
      if (a.rfind("lm=", 0) == 0) p.levenberg = std::atof(a.c_str() + 3);
      if (a.rfind("rows=", 0) == 0) p.rows = std::atoi(a.c_str() + 5);
      if (a.rfind("fine=", 0) == 0) p.fine_mm = std::atof(a.c_str() + 5);
      if (a.rfind("central=", 0) == 0) p.central = std::atof(a.c_str() + 8);
      if (a.rfind("ends=", 0) == 0) p.ends = std::atof(a.c_str() + 5);
      if (a.rfind("coarse=", 0) == 0) p.coarse_mm = std::atof(a.c_str() + 7);
      if (a.rfind("gap=", 0) == 0) p.gap_mm = std::atof(a.c_str() + 4);
      if (a.rfind("cgrowth=", 0) == 0) p.column_growth = std::atof(a.c_str() + 8);
      if (a.rfind("rgrowth=", 0) == 0) p.row_growth = std::atof(a.c_str() + 8);
      if (a.rfind("vtk=", 0) == 0) p.vtk = a.substr(4);
      if (a == "profile") p.profile = true;
      if (a == "land") p.land = true;
      if (a == "diagnose") p.diagnose = true;
      if (a.rfind("fillet=", 0) == 0) p.fillet_mm = std::atof(a.c_str() + 7);
      if (a.rfind("tip=", 0) == 0) p.tip_mm = std::atof(a.c_str() + 4);
      if (a.rfind("bc=", 0) == 0) p.end_condition = a.substr(3);
      if (a.rfind("section=", 0) == 0) p.section_x = std::atof(a.c_str() + 8);
      if (a.rfind("csv=", 0) == 0) p.csv = a.substr(4);
      if (a.rfind("oracle=", 0) == 0) p.oracle = a.substr(7);
      if (a.rfind("tol=", 0) == 0) p.tolerance = std::atof(a.c_str() + 4);
      if (a.rfind("grow=", 0) == 0) p.growth = std::atoi(a.c_str() + 5);
      if (a.rfind("bodyds=", 0) == 0) p.body_sampling_mm = std::atof(a.c_str() + 7);
      if (a == "inertia") p.inertia = true;
      if (a == "hold") p.hold = true;
      if (a.rfind("flank=", 0) == 0) p.flank = std::atof(a.c_str() + 6);
      if (a.rfind("tflank=", 0) == 0) p.tflank = std::atof(a.c_str() + 7);
      if (a.rfind("turn=", 0) == 0) p.turn = std::atof(a.c_str() + 5);
      if (a.rfind("vflank=", 0) == 0) p.vflank = std::atof(a.c_str() + 7);
      if (a.rfind("branch=", 0) == 0) p.branch = std::atof(a.c_str() + 7);
      if (a.rfind("cycles=", 0) == 0) p.cycles = std::atoi(a.c_str() + 7);
      if (a.rfind("field=", 0) == 0) {
        const std::string spec = a.substr(6);
        std::size_t at = spec.find(':');
        p.field_prefix = spec.substr(0, at);
        while (at != std::string::npos) {
          p.field_at_mm.push_back(std::atof(spec.c_str() + at + 1));
          at = spec.find(':', at + 1);
        }
      }
      if (a.rfind("threads=", 0) == 0) p.threads = std::atoi(a.c_str() + 8);
      if (a.rfind("krylov=", 0) == 0) p.krylov = std::atoi(a.c_str() + 7);
      if (a == "plainpressure") p.plain_pressure = true;
      if (a == "linearpred") p.linear_predictor = true;
      if (a.rfind("ktol=", 0) == 0) p.krylov_tolerance = std::atof(a.c_str() + 5);
      if (a.rfind("dense=", 0) == 0) std::sscanf(a.c_str() + 6, "%lf:%lf:%lf", &p.dense[0], &p.dense[1], &p.dense[2]);
      if (a.rfind("loads=", 0) == 0) std::sscanf(a.c_str() + 6, "%lf:%lf", &p.loads[0], &p.loads[1]);
    }
    std::printf("%s", kProbeHeader);
    Outcome o;
    try {
      o = run_probe(p);
    } catch (const std::exception& e) {
      std::printf("failed: %s\n", e.what());
      return 4;
    }
    print_probe(p, o);
    std::printf("main thread CPU %.2f s (the wall time on an idle machine, nearly), wall %.2f s\n", o.main_cpu_s, o.wall_s);
    if (p.branch > 0.0) std::printf("branch switches: %d increments carried\n", o.life.run.final_state.branch_switches);
    std::printf("unsymmetric tangents: %d GMRES iterations, %d fell back to the LU\n",
                o.life.run.final_state.krylov_iterations, o.life.run.final_state.krylov_fallbacks);
    std::printf("equilibrium %.3g; spans: cord-line reactions <= %.3g of F/B, mid-section balance %.3g\n",
                o.life.run.equilibrium_error, o.life.run.span_cord_share, o.life.run.span_section_mismatch);
    std::printf("flank foundation k %.4g N/mm^4: radial force against Report I's dead load (increments with >= half "
                "its largest) largest %+.3g, mean %+.3g\n",
                o.life.run.flank_stiffness_N_mm4, o.life.run.flank_radial_share, o.life.run.flank_radial_mean_share);
    if (o.life.run.flank_stick_N_mm4 > 0.0 || p.vflank > 0.0 || p.turn > 0.0)
      std::printf("flank along the belt (stick k_t %.4g N/mm^4, sliding floor %.4g mm/s): largest longitudinal force %.3g "
                  "of Report I's largest dead friction\n",
                  o.life.run.flank_stick_N_mm4, p.vflank, o.life.run.flank_stick_share);
    const segment::MeshKnobs m = o.mesh;
    const segment::MeshQuality q = segment::mesh_quality(segment::build_mesh(scene::cog_section(probe_scene(p)), m));
    std::printf("mesh: fine %.3g mm, coarse %.3g mm, %d cushion rows, gap %.3g mm, column growth %.3g, row growth "
                "%.3g, %s; min det J / mean %.3f, max aspect ratio %.2f\n",
                m.fine_size_mm, m.coarse_size_mm, m.cushion_rows, m.gap_size_mm, m.column_growth, m.row_growth,
                segment::to_string(o.integration), q.min_jacobian_ratio, q.max_aspect_ratio);
    const fatigue::ModeLife& n1 = o.life.report.modes[0];
    std::printf("N1 at %s (%.3f, %.3f): peaks", n1.design_point.c_str(), n1.x_mm, n1.y_mm);
    for (const fatigue::Peak& q : n1.peaks) std::printf(" %.4f MPa at %.4f s;", q.stress_MPa, q.t_s);
    std::printf("\n");
    print_cushion_points(p, o);
    if (!p.csv.empty()) segment::write_cycle_csv(o.life.run, p.csv);
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "meshconv") {  // table 5 only
    complete_convergence();
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "uncertainty") {  // table 7 only
    uncertainty_table();
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "scan") {  // table 9 only
    scan_table();
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "heatlevels") {  // table 11 only
    heat_level_table(argc > 2 && std::string(argv[2]) == "temperatures");
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "heat") {  // table 6 only
    heat_table();
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "calibration") {  // the level calibration's held-out table only
    bench_life::calibration_table(kRoot + "/datasets/drives", windowed_card_file("material-1"),
                                  windowed_card_file("material-2"));
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "levels") {  // table 1 only, with the complete rows
    level_table({"beam", "elastic", "complete", "complete held"});
    return 0;
  }
  const bool quick = argc > 1 && std::string(argv[1]) == "quick";  // no complete rows (minutes each)
  level_table(quick ? std::vector<const char*>{"beam", "elastic"}
                    : std::vector<const char*>{"beam", "elastic", "complete", "complete held"});
  convergence("iso");
  convergence("elastic");
  if (!quick) complete_convergence();  // the medium drive's complete level stops at its fold
  if (!quick)
    bench_life::calibration_table(kRoot + "/datasets/drives", windowed_card_file("material-1"),
                                  windowed_card_file("material-2"));
  beam_sweep();
  heat_table();
  uncertainty_table();
  if (!quick) scan_table();
  return 0;
}
