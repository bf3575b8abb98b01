// The segment driven by the load cycle (fitlib/segment/cycle.hpp; docs/segment.md).
#include "fitlib/segment/cycle.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>

#include "cycle_dissipation.hpp"
#include "cycle_observers.hpp"
#include "cycle_parts.hpp"
#include "cycle_repeat.hpp"
#include "cycle_split.hpp"
#include "element.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/end_faces.hpp"
#include "fitlib/segment/flank.hpp"

namespace fitlib::segment {
namespace {

// Intervals per side of the cord curve (cord_curve; the knob no test or benchmark varied, issue 32).
constexpr int kCurveIntervals = 24;

double reference_area(const Mesh& m, int e, const std::vector<detail::GaussPoint>& rule) {
  double area = 0.0;
  for (const auto& g : rule) area += reference_jacobian(m, e, g.xi, g.eta) * g.weight;
  return area;
}

}  // namespace

void flank_shares(CycleResult& run) {
  double largest = 0.0, sum = 0.0;
  int count = 0;
  for (const IncrementLoads& q : run.loads) largest = std::max(largest, q.contact_radial_N_mm);
  run.flank_radial_share = run.flank_radial_mean_share = 0.0;
  for (const IncrementLoads& q : run.loads)
    if (largest > 0.0 && q.contact_radial_N_mm >= 0.5 * largest) {
      const double share = q.flank_radial_N_mm / q.contact_radial_N_mm;
      if (std::abs(share) > std::abs(run.flank_radial_share)) run.flank_radial_share = share;
      sum += share, ++count;
    }
  if (count) run.flank_radial_mean_share = sum / count;
  double dead = 0.0, stick = 0.0;  // the stick's longitudinal total against the dead friction's
  for (const IncrementLoads& q : run.loads)
    dead = std::max(dead, std::abs(q.contact_longitudinal_N_mm)), stick = std::max(stick, std::abs(q.flank_longitudinal_N_mm));
  run.flank_stick_share = dead > 0.0 ? stick / dead : 0.0;  // 0 without a law along the belt
}

double span_cord_share_bound(const CycleResult& run) {
  using B = EquilibriumBounds;
  if (run.history) return B::span_cord_share_with_history;
  return run.sheared_ends ? B::span_cord_share_sheared_ends : B::span_cord_share;
}

Eigen::Vector2d contact_body_force(const belt::LoadState& q, const CycleDrive& d) {
  if (!(q.p_MPa > 0.0)) return Eigen::Vector2d::Zero();
  const double cb = std::cos(d.wedge_half_angle_rad), sb = std::sin(d.wedge_half_angle_rad);
  const double area_factor = q.p_MPa * 2.0 / d.width_mm / cb;  // cos β_s = 1 (docs/decisions.md)
  const double inertia = d.density_kg_m3 * 1e-12 * q.K_1_mm * d.speed_mm_s * d.speed_mm_s;  // ρKV², N/mm³
  // μ is the load cycle's friction used: the drive's μ, ramped to zero and back at the driver's
  // exit (belt-mechanics.md §2.5), as the beam level reads it.
  const double B_l = -q.friction_used * area_factor * std::sin(q.gamma_rad);                  // (6.6)
  const double B_r = area_factor * (sb - q.friction_used * std::cos(q.gamma_rad)) + inertia;   // (6.7)
  return {B_l, B_r};
}

namespace {

// Periodic moving average of v over ±half_width cells (the total is kept).
std::vector<double> windowed(const std::vector<double>& v, int half_width) {
  const int M = static_cast<int>(v.size());
  if (half_width <= 0) return v;
  std::vector<double> prefix(3 * M + 1, 0.0), out(M);  // v three times over: the window never leaves it
  for (int i = 0; i < 3 * M; ++i) prefix[i + 1] = prefix[i] + v[i % M];
  const int w = std::min(half_width, M / 2 - 1);
  for (int i = 0; i < M; ++i) {
    const int lo = i - w + M;  // cells i − w … i + w, shifted by one period
    out[i] = (prefix[lo + 2 * w + 1] - prefix[lo]) / (2 * w + 1);
  }
  return out;
}

}  // namespace

std::vector<double> cycle_breakpoints(const belt::LoadHistory& h, int steps, double weight, double reach_mm) {
  if (steps < 1) throw core::UsageError("segment cycle: steps_per_cycle must be ≥ 1");
  const int M = 4000;
  const double L = h.length_mm(), ds = L / M;
  std::vector<double> dK(M), dp(M);
  double tvK = 0.0, tvp = 0.0;
  for (int i = 0; i < M; ++i) {
    const belt::LoadState a = h.at_position(i * ds), b = h.at_position((i + 1) * ds);
    dK[i] = std::abs(b.K_1_mm - a.K_1_mm), dp[i] = std::abs(b.p_MPa - a.p_MPa);
    tvK += dK[i], tvp += dp[i];
  }
  // The segment feels a change while any of it is over it: spread each change over ±reach.
  const int half_width = static_cast<int>(std::lround(reach_mm / ds));
  dK = windowed(dK, half_width), dp = windowed(dp, half_width);
  std::vector<double> cumulative(M + 1, 0.0);
  for (int i = 0; i < M; ++i)
    cumulative[i + 1] = cumulative[i] + 1.0 / M + weight * 0.5 * ((tvK > 0 ? dK[i] / tvK : 0.0) + (tvp > 0 ? dp[i] / tvp : 0.0));
  // The cycle's end is not searched: back() · steps / steps can round above back(), where lower_bound
  // returns end() (a read past the table, found by the sanitizer build); the clamp guards the rest.
  std::vector<double> tau;
  for (int k = 1; k < steps; ++k) {
    const double target = cumulative.back() * k / steps;
    const int i = std::min(M, static_cast<int>(std::lower_bound(cumulative.begin(), cumulative.end(), target) -
                                               cumulative.begin()));
    const double s = i == 0 ? 0.0 : (i - 1 + (target - cumulative[i - 1]) / (cumulative[i] - cumulative[i - 1])) / M;
    if (tau.empty() || s > tau.back() + 1e-9) tau.push_back(s);
  }
  if (tau.empty() || 1.0 > tau.back() + 1e-9) tau.push_back(1.0);  // the cycle's end
  return tau;
}

namespace {

// Where the last converged increment was, in the user's terms: the bending step, or the cycle and
// the path position with the load there (the message's prefix).
std::string where_in_cycle(double tau, const belt::LoadHistory& h) {
  std::ostringstream m;
  m << "segment load cycle: ";
  if (tau < 1.0) {
    m << "failed in the bending step (" << core::format_number(100.0 * tau, 3) << " % of it); ";
    return m.str();
  }
  const int cycle = static_cast<int>(std::floor(tau - 1.0)) + 1;
  const double s = (tau - cycle) * h.length_mm();
  const belt::LoadState at = h.at_position(s);
  m << "failed in cycle " << cycle << " after path position " << core::format_number(s, 4) << " mm of "
    << core::format_number(h.length_mm(), 4) << " mm from the slack span's middle (curvature "
    << core::format_number(at.K_1_mm, 4) << " 1/mm, side pressure " << core::format_number(at.p_MPa, 4)
    << " MPa there); ";
  return m.str();
}

}  // namespace

int conditioning_increments(const CycleStepping& s) {
  return s.conditioning_steps > 0 ? s.conditioning_steps : s.steps_per_cycle;
}

int planned_increments(const CycleStepping& s) {
  return s.bend_steps + (s.cycles - 1) * conditioning_increments(s) + s.steps_per_cycle;
}

namespace {

void check_cycle_inputs(const CycleDrive& drive, const CycleStepping& stepping) {
  if (!drive.history) throw core::UsageError("segment cycle: a load history is required");
  if (!(drive.speed_mm_s > 0.0)) throw core::InputError("segment cycle: the belt speed must be > 0 (a belt at rest has no load cycle)");
  if (stepping.cycles < 1) throw core::InputError("segment cycle: cycles must be ≥ 1");
  const std::vector<double>& at_s = stepping.positions_mm;
  for (std::size_t k = 0; k < at_s.size(); ++k)
    if (!(at_s[k] > (k ? at_s[k - 1] : 0.0)) || !std::isfinite(at_s[k]))
      throw core::UsageError("segment cycle: positions_mm must be positive and increasing");
}

// The run's load levels: step 1's equal increments, then step 2's breakpoints (the cycles' planned
// ones, or the given path positions), λ = τ / T.
std::vector<double> load_schedule(const CycleStepping& stepping, const belt::LoadHistory& h, double T,
                                  double half_length_mm) {
  std::vector<double> schedule;
  for (int i = 1; i <= stepping.bend_steps; ++i) schedule.push_back(static_cast<double>(i) / stepping.bend_steps / T);
  if (!stepping.positions_mm.empty()) {
    for (double s_mm : stepping.positions_mm) schedule.push_back(std::min(1.0, (1.0 + s_mm / h.length_mm()) / T));
    return schedule;
  }
  const std::vector<double> per_cycle =
      cycle_breakpoints(h, stepping.steps_per_cycle, stepping.change_weight, half_length_mm);
  const std::vector<double> conditioning =
      cycle_breakpoints(h, conditioning_increments(stepping), stepping.change_weight, half_length_mm);
  for (int c = 0; c < stepping.cycles; ++c)
    for (double b : c + 1 < stepping.cycles ? conditioning : per_cycle) {
      const double lambda = std::min(1.0, (1.0 + c + b) / T);
      if (schedule.empty() || lambda > schedule.back() + 1e-12) schedule.push_back(lambda);
    }
  return schedule;
}

// Per element: its reference area (rule of `order`), its unstrained path extent and centre.
detail::ElementSampling element_extents(const Mesh& m, const std::vector<double>& path_x, int order,
                                        double sampling_mm, std::vector<double>& area) {
  const auto rule = detail::gauss_rule(order);
  area.assign(m.element_count(), 0.0);
  detail::ElementSampling sampling{std::vector<double>(m.element_count()),
                                   std::vector<std::pair<double, double>>(m.element_count()), sampling_mm};
  for (int e = 0; e < m.element_count(); ++e) {
    area[e] = reference_area(m, e, rule);
    auto& extent = sampling.extent_x[e];
    extent = {path_x[m.elements[e][0]], path_x[m.elements[e][0]]};
    for (int a = 0; a < 4; ++a) {
      const double x = path_x[m.elements[e][a]];
      sampling.centre_x[e] += 0.25 * x;
      extent = {std::min(extent.first, x), std::max(extent.second, x)};
    }
  }
  return sampling;
}

// The run's results beside the observers': counts, flags and the flank's shares.
void summarise(const StaticSolution& final_state, const Mesh& m, const CyclePhysics& physics, bool history,
               bool sheared_ends, CycleResult& out) {
  out.increments = final_state.increments;
  out.newton_iterations = final_state.newton_iterations;
  out.cuts = final_state.cuts;
  out.factorizations = final_state.factorizations;
  out.elements = m.element_count();
  out.history = history;
  out.sheared_ends = sheared_ends;
  out.equations = final_state.equations;
  out.flank_stiffness_N_mm4 = physics.flank_stiffness_N_mm4;
  out.flank_stick_N_mm4 = physics.flank_stick_N_mm4;
  flank_shares(out);
}

}  // namespace

namespace {

// CyclePhysics::element_laws checked against the mesh and the role laws (StaticProblem::element_laws).
std::vector<const PlaneStrainLaw*> element_laws(const Mesh& m, const std::array<const PlaneStrainLaw*, 2>& laws,
                                                const std::vector<const PlaneStrainLaw*>& given) {
  if (given.empty()) return given;
  if (static_cast<int>(given.size()) != m.element_count())
    throw core::UsageError("segment cycle: element_laws has " + std::to_string(given.size()) + " laws for " +
                           std::to_string(m.element_count()) + " elements");
  for (int e = 0; e < m.element_count(); ++e) {
    const PlaneStrainLaw* law = given[e];
    if (law && (law->state_size() != 0 || law->symmetric_tangent() != laws[static_cast<int>(m.roles[e])]->symmetric_tangent()))
      throw core::UsageError("segment cycle: element " + std::to_string(e) + "'s law carries history or another "
                             "tangent symmetry than its role's");
  }
  return given;
}

// solve_static over the load schedule; a failure's message says where in the cycle it was.
StaticSolution solve_over_cycle(const StaticProblem& p, const SolverKnobs& solver, std::vector<double> schedule,
                                const detail::ProgressReport& progress, double T, const belt::LoadHistory& h) {
  SolverKnobs k = solver;
  k.stepping.schedule = std::move(schedule);
  try {
    return solve_static(p, k);
  } catch (const core::NumericalError& e) {
    throw core::NumericalError(where_in_cycle(progress.last_lambda() * T, h) + e.what());
  }
}

}  // namespace

namespace {

// The run's geometry and pseudo time: the straight and moulded meshes, each node's unstrained path
// position, T (λ τ = T), the period, and the frame the problem and the observers read (the cord
// curve at λ). Built in place and never copied: the frame points into it.
struct CycleGeometry {
  CycleGeometry(const CogSection& section, const MeshKnobs& mesh_knobs, const CycleDrive& drive, const CycleKnobs& knobs)
      : h(*drive.history),
        straight(build_mesh(section, mesh_knobs)),
        K_m(knobs.physics.manufactured_radius_mm > 0.0 ? 1.0 / knobs.physics.manufactured_radius_mm : 0.0),
        m(detail::wrapped(straight, K_m)),
        reach(1.5 * straight.half_length_mm),
        T(1.0 + (knobs.stepping.positions_mm.empty() ? knobs.stepping.cycles
                                                     : knobs.stepping.positions_mm.back() / h.length_mm())),
        period(h.period_s() > 0.0 ? h.period_s() : h.length_mm() / drive.speed_mm_s),
        integral(h) {
    for (const Eigen::Vector2d& X : straight.X) path_x.push_back(X.x());
    const int n = kCurveIntervals;
    frame = detail::CycleFrame{&m, &path_x, &h, T, period,
                               [&h = h, &integral = integral, K_m = K_m, reach = reach, n, T = T](double lambda) {
                                 return detail::cord_curve(lambda * T, h, integral, K_m, reach, n);
                               }, std::nullopt, 0.0};
  }
  CycleGeometry(const CycleGeometry&) = delete;
  CycleGeometry& operator=(const CycleGeometry&) = delete;

  const belt::LoadHistory& h;
  const Mesh straight;
  const double K_m;
  const Mesh m;
  std::vector<double> path_x;
  const double reach, T, period;
  const detail::CurvatureIntegral integral;
  detail::CycleFrame frame;
};

// The cord-curve problem of the run, before its loads: the end faces (radial, free, or sheared by
// the long belt's profiles or the given ones, returned in warping and shear), the per-element laws,
// the time, the temperature and the rubber's mass.
StaticProblem cycle_problem(const CycleGeometry& g, const CogSection& section,
                            const std::array<const PlaneStrainLaw*, 2>& laws, const CycleDrive& drive,
                            const CyclePhysics& physics, CyclePhysics::EndProfile& warping,
                            CyclePhysics::EndProfile& shear) {
  warping = physics.end_warping_mm, shear = physics.end_shear_MPa;
  if (physics.ends == EndCondition::sheared && !warping && !shear)
    detail::long_belt_ends(section, g.straight, laws, drive, warping, shear);
  const EndCondition ends = physics.ends == EndCondition::free ? EndCondition::free : EndCondition::radial;
  StaticProblem p =
      cord_curve_problem(g.m, g.path_x, laws, g.frame.curve_at, ends, detail::end_shift(g.straight, g.h, g.T, warping));
  p.element_laws = element_laws(g.m, laws, physics.element_laws);
  p.time_s = [T = g.T, period = g.period](double lambda) { return lambda * T * period; };
  p.temperature_C = drive.temperature_C;
  p.density_t_mm3 = drive.density_kg_m3 * 1e-12;  // the rubber's mass when PhysicsOptions::inertia is on
  return p;
}

// The loads (segment/load.hpp), one line each: Report I's contact pressure, friction and radial
// inertia (6.6–6.9), the deformation-limited flank (segment/flank.hpp), the end faces' shear; and
// the equilibrium check's inputs that go with them. Returns the elements' path extents.
detail::ElementSampling add_cycle_loads(StaticProblem& p, const CycleGeometry& g, const CycleDrive& drive,
                                        const CyclePhysics& physics, Integration integration, int order,
                                        const CyclePhysics::EndProfile& shear, detail::EquilibriumCheck::Inputs& check) {
  const detail::ElementSampling sampling =
      element_extents(g.m, g.path_x, order, physics.body_force_sampling_mm, check.area_mm2);
  check.body = detail::contact_body_forces(sampling, drive, g.T, g.frame.curve_at);
  p.loads.push_back(dead_body_force(g.m.element_count(), check.body));
  check.along_belt = physics.flank_along_belt();  // a tangential flank law
  if (physics.flank_stiffness_N_mm4 > 0.0 || check.along_belt)
    p.loads.push_back(flank_contact(g.m, g.path_x, integration, NeutralCurve::uniform(g.K_m, 0.0, g.reach),
                                    g.frame.curve_at, physics.flank_stick_N_mm4 > 0.0, physics.flank_slide_floor_mm_s > 0.0,
                                    physics.flank_turn_N_mm4 > 0.0,
                                    detail::flank_levels(sampling, drive, physics, g.T, p.time_s)));
  if (shear) {
    check.nodal = detail::end_shear_forces(g.m.node_count(), g.straight, g.path_x, g.h, g.T, g.frame.curve_at, shear);
    p.loads.push_back(dead_nodal_force(check.nodal));
  }
  check.problem = &p, check.centre_x_mm = sampling.centre_x;
  check.width_mm = drive.width_mm, check.integration = integration;
  return sampling;
}

// Every increment of the run solved: composed of the cycle's parts (cycle_parts.hpp: reference,
// cord curve, loads) and observers (cycle_observers.hpp), solved by solve_static over the load schedule.
CycleResult solve_cycles(const CogSection& section, const MeshKnobs& mesh_knobs, const SolverKnobs& solver,
                         const std::array<const PlaneStrainLaw*, 2>& laws, const CycleDrive& drive,
                         const CycleKnobs& knobs, const std::vector<NamedPoint>& extra_points) {
  const CycleGeometry g(section, mesh_knobs, drive, knobs);
  CyclePhysics::EndProfile warping, shear;
  StaticProblem p = cycle_problem(g, section, laws, drive, knobs.physics, warping, shear);
  const int order = gauss_order(g.m, solver.physics.integration);
  detail::EquilibriumCheck::Inputs check;
  const detail::ElementSampling sampling =
      add_cycle_loads(p, g, drive, knobs.physics, solver.physics.integration, order, shear, check);

  CycleResult out;
  out.cycle_time_s = g.period;
  std::vector<NamedPoint> named = standard_points(section);
  named.insert(named.end(), extra_points.begin(), extra_points.end());
  detail::ProgressReport progress(knobs.outputs.progress);
  detail::PointMonitor points(g.frame, g.straight, g.K_m, named, order, out.points);
  detail::FieldSnapshots fields(g.frame, knobs, out.vtk_files);
  detail::CycleDissipation dissipation(g.frame, check.area_mm2, sampling.centre_x, section.cog_pitch_mm, drive.width_mm,
                                       out.dissipation_J_mm);
  detail::EquilibriumCheck equilibrium(g.frame, std::move(check), out);
  p.observers = {&progress, &points, &equilibrium, &dissipation};
  if (!knobs.outputs.vtk_prefix.empty()) p.observers.insert(p.observers.begin() + 2, &fields);
  std::optional<detail::RegionScan> scan;
  if (knobs.outputs.scan_design_regions)
    p.observers.push_back(&scan.emplace(g.frame, g.straight, g.K_m, section, mesh_knobs, order, out.scanned));
  std::optional<detail::ElementMeans> element_means;
  if (knobs.outputs.record_elements) p.observers.push_back(&element_means.emplace(g.frame, g.straight, out.element_means));

  out.final_state = solve_over_cycle(p, solver, load_schedule(knobs.stepping, g.h, g.T, g.straight.half_length_mm),
                                     progress, g.T, g.h);
  const bool history = laws[0]->state_size() > 0 || laws[1]->state_size() > 0;
  summarise(out.final_state, g.m, knobs.physics, history, static_cast<bool>(warping) || static_cast<bool>(shear), out);
  return out;
}

}  // namespace

// A run without history solves the bend and one cycle, copied to the later ones (cycle_repeat.hpp).
CycleResult run_cycle(const CogSection& section, const MeshKnobs& mesh_knobs, const SolverKnobs& solver,
                      const std::array<const PlaneStrainLaw*, 2>& laws, const CycleDrive& drive,
                      const CycleKnobs& knobs, const std::vector<NamedPoint>& extra_points) {
  check_cycle_inputs(drive, knobs.stepping);
  if (!detail::repeats_first_cycle(laws, knobs, solver))
    return solve_cycles(section, mesh_knobs, solver, laws, drive, knobs, extra_points);
  CycleKnobs one = knobs;
  one.stepping.cycles = 1;
  const detail::CycleSolve solve = [&](const CycleDrive& d, const CycleKnobs& k, const SolverKnobs& s) {
    return solve_cycles(section, mesh_knobs, s, laws, d, k, extra_points);
  };
  CycleResult out = knobs.stepping.split_history_free_cycle && knobs.outputs.vtk_prefix.empty()
                        ? detail::solve_history_free_cycle(solve, section, mesh_knobs, laws, drive, one, solver)
                        : solve(drive, one, solver);
  detail::repeat_first_cycle(out, knobs.stepping.cycles, drive.history->length_mm());
  return out;
}

void write_cycle_csv(const CycleResult& r, const std::string& path) {
  // Rendered whole, then core's writer (the rename here was unchecked, and replaced a device).
  std::ostringstream f;
  f.precision(9);
  f << "point,role,x_mm,y_mm,t_s,s_mm,s11_MPa,s22_MPa,s12_MPa,s33_MPa,e11,e22,e12\n";
  for (const MonitoredHistory& mh : r.points)
    for (const CycleSample& c : mh.samples) {
      for (double v : {c.s11_MPa, c.s22_MPa, c.s12_MPa, c.s33_MPa, c.e11, c.e22, c.e12})
        if (!std::isfinite(v)) throw core::NumericalError("segment cycle: non-finite value at '" + mh.point.name + "'");
      f << mh.point.name << ',' << to_string(mh.role) << ',' << mh.point.x_mm << ',' << mh.point.y_mm << ','
        << c.t_s << ',' << c.s_mm << ',' << c.s11_MPa << ',' << c.s22_MPa << ',' << c.s12_MPa << ','
        << c.s33_MPa << ',' << c.e11 << ',' << c.e22 << ',' << c.e12 << '\n';
    }
  core::write_file_atomically(path, f.str());
}

}  // namespace fitlib::segment