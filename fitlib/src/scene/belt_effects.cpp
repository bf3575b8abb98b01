// Belt-mechanics effects of a scene: the load cycle's timing and refinement changes, the
// Sorge–Cammalleri steady drive, Sorge's CVT formulary, the tension test.
#include <algorithm>
#include <cmath>

#include "effects.hpp"
#include "fitlib/belt/cvt.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::scene::detail {
namespace {
using core::InputError;
using core::kPi;

// Largest relative change of a column between two load cycles sampled at the same s.
double relative_change(const belt::LoadCycle& a, const belt::LoadCycle& b,
                       double belt::LoadSample::*field) {
  auto at = [&](const belt::LoadCycle& c, double s) {
    const auto& x = c.samples;
    auto it = std::lower_bound(x.begin(), x.end(), s,
                               [](const belt::LoadSample& q, double v) { return q.s_mm < v; });
    if (it == x.end()) return x.back().*field;
    return (*it).*field;
  };
  double scale = 0.0, diff = 0.0;
  for (const auto& q : a.samples) {
    scale = std::max(scale, std::abs(q.*field));
    diff = std::max(diff, std::abs(q.*field - at(b, q.s_mm)));
  }
  return scale > 0.0 ? diff / scale : 0.0;
}

// ρAv², N.
double centrifugal_tension_N(const belt::DriveCase& d) {
  return d.belt.density_kg_m3 * d.belt.area_mm2 * d.belt_speed_mm_s * d.belt_speed_mm_s * 1e-12;
}

}  // namespace

double best_of_three(const belt::DriveCase& drive, const belt::LoadCycleOptions& options,
                     belt::LoadCycle& out) {
  double best = INFINITY;
  for (int k = 0; k < 3; ++k) {
    core::Stopwatch w;
    out = belt::compute_load_cycle(drive, options);
    best = std::min(best, w.seconds());
  }
  return best;
}

EffectChange effect_change(const belt::LoadCycle& with, const belt::LoadCycle& without) {
  return {relative_change(with, without, &belt::LoadSample::F_N),
          relative_change(with, without, &belt::LoadSample::p_MPa),
          relative_change(with, without, &belt::LoadSample::gamma_rad),
          relative_change(with, without, &belt::LoadSample::K_1_mm),
          relative_change(with, without, &belt::LoadSample::friction_used)};
}

// Sorge's formulary (12a,b) on the scene's drive: dynamic tensions T = F − ρAv², wraps from the
// geometry unless [cvt] gives them.
CvtThrust cvt_thrust(const belt::DriveCase& d, const CvtSpec& c, const belt::LoadCycle* cycle) {
  const auto& g = d.geometry;
  const std::size_t drv = belt::driver_index(g);
  const std::size_t dvn = (drv + 1) % g.pulleys.size();
  const double F_c = centrifugal_tension_N(d);
  CvtThrust t;
  t.slack_tension_N = c.slack_tension_N > 0 ? c.slack_tension_N : d.span_tension_N[drv] - F_c;
  t.tight_tension_N = c.tight_tension_N > 0 ? c.tight_tension_N : d.span_tension_N[dvn] - F_c;
  t.groove_half_angle_deg = c.groove_half_angle_deg;
  const double alpha = c.groove_half_angle_deg * kPi / 180.0;
  t.driver_wrap_rad = c.driver_wrap_rad > 0 ? c.driver_wrap_rad : g.wrap_rad[drv];
  t.driven_wrap_rad = c.driven_wrap_rad > 0 ? c.driven_wrap_rad : g.wrap_rad[dvn];
  t.driver_axial_thrust_N = belt::driver_axial_thrust_N(t.tight_tension_N, alpha, t.driver_wrap_rad);
  t.driven_axial_thrust_N =
      belt::driven_axial_thrust_N(t.tight_tension_N, t.slack_tension_N, alpha, t.driven_wrap_rad);
  if (cycle) {  // the 1-D thrust of the load cycle next to the formulary
    t.load_cycle_driver_axial_thrust_N = belt::axial_thrust_N(*cycle, d.belt, static_cast<int>(drv));
    t.load_cycle_driven_axial_thrust_N = belt::axial_thrust_N(*cycle, d.belt, static_cast<int>(dvn));
  }
  return t;
}

// Sorge–Cammalleri steady drive on the scene's two-pulley drive: S = c with the drive-time
// constants (belt::drive_time_belt), tensions F − ρAv² when the scene's `inertia` effect is on,
// else the static tensions F.
ViscoelasticTension viscoelastic_tension(const belt::DriveCase& d, bool inertia) {
  const auto& g = d.geometry;
  if (g.pulleys.size() != 2)
    throw InputError("viscoelastic_tension handles two-pulley drives only", {}, 0, 0, "effects.viscoelastic_tension");
  const std::size_t drv = belt::driver_index(g);
  belt::ViscoelasticDriveInput in;
  in.radius_mm = g.pulleys[drv].pitch_radius_mm;
  if (!(d.belt_speed_mm_s > 0.0))
    throw InputError("viscoelastic_tension needs the driver's speed_rpm", {}, 0, 0, "drive.pulleys");
  in.omega_rad_s = d.belt_speed_mm_s / in.radius_mm;
  in.center_distance_mm = g.spans[drv].length_mm;
  in.friction = d.friction;
  in.belt = belt::drive_time_belt(d.belt.c_N, in.omega_rad_s);
  const double F_c = inertia ? centrifugal_tension_N(d) : 0.0;
  in.slack_N = d.span_tension_N[drv] - F_c;
  in.tight_N = d.span_tension_N[1 - drv] - F_c;
  return {in.belt, belt::solve_viscoelastic_drive(in)};
}

// Sorge–Cammalleri load/unload test on the scene's two pulleys: d0 = the driver's span's centre
// distance, r = the driver's radius.
TensionTest tension_test(const belt::DriveCase& d, const TensionTestSpec& t, double friction) {
  const auto& g = d.geometry;
  const std::size_t i = belt::driver_index(g);
  belt::TensionTestInput in;
  in.belt = {t.S_N.value_or(d.belt.c_N), t.tau_T_s, t.tau_eps_s};
  in.d0_mm = g.spans[i].center_distance_mm;
  in.r_mm = g.pulleys[i].pitch_radius_mm;
  in.f = friction;
  in.v_mm_s = t.rate_mm_min / 60.0;
  in.load_time_s = t.load_time_s;
  in.nodes = t.nodes;
  in.steps_per_phase = t.steps;
  return {in.belt, belt::simulate_tension_test(in)};
}

}  // namespace fitlib::scene::detail
