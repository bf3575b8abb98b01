#include "fitlib/scene/planner.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <sstream>

#include "fitlib/belt/cvt.hpp"
#include "fitlib/belt/stiffness.hpp"
#include "fitlib/belt/viscoelastic.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::scene {
namespace {
using core::InputError;
using core::kPi;

bool flag(const std::map<std::string, bool>& m, const std::string& k) {
  auto it = m.find(k);
  return it != m.end() && it->second;
}

double storage_modulus_MPa(const card::Card& c, const std::string& role, const char* orientation,
                           double f_Hz, double amplitude, double T_C) {
  try {
    const auto model = c.model();
    const auto values = c.values();
    model::TestCondition tc;
    tc.mode = model::TestMode::uniaxial;
    tc.orientation = orientation;
    tc.frequency_Hz = f_Hz;
    tc.temperature_C = T_C;
    tc.strain_amplitude = amplitude;
    return model->moduli(values.data(), tc).storage;
  } catch (const std::exception& e) {  // e.g. a shear card asked for a uniaxial modulus
    throw InputError(std::string("card cannot give the uniaxial storage modulus the belt needs: ") + e.what(),
                     {}, 0, 0, "belt.materials." + role);
  }
}

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

// Sorge's formulary (12a,b) on the scene's drive: dynamic tensions T = F − ρAv², wraps from the
// geometry unless [cvt] gives them.
nlohmann::json cvt_thrust_json(const belt::DriveCase& d, const CvtSpec& c) {
  const auto& g = d.geometry;
  const std::size_t drv = belt::driver_index(g);
  std::size_t dvn = (drv + 1) % g.pulleys.size();
  const double F_c = d.belt.density_kg_m3 * d.belt.area_mm2 * d.belt_speed_mm_s * d.belt_speed_mm_s * 1e-12;
  const double T_S = c.slack_tension_N > 0 ? c.slack_tension_N : d.span_tension_N[drv] - F_c;
  const double T_T = c.tight_tension_N > 0 ? c.tight_tension_N : d.span_tension_N[dvn] - F_c;
  const double alpha = c.groove_half_angle_deg * kPi / 180.0;
  const double wrap_R = c.driver_wrap_rad > 0 ? c.driver_wrap_rad : g.wrap_rad[drv];
  const double wrap_N = c.driven_wrap_rad > 0 ? c.driven_wrap_rad : g.wrap_rad[dvn];
  return {{"tight_tension_N", T_T}, {"slack_tension_N", T_S}, {"groove_half_angle_deg", c.groove_half_angle_deg},
          {"driver_wrap_deg", wrap_R * 180 / kPi}, {"driven_wrap_deg", wrap_N * 180 / kPi},
          {"driver_axial_thrust_N", belt::driver_axial_thrust_N(T_T, alpha, wrap_R)},
          {"driven_axial_thrust_N", belt::driven_axial_thrust_N(T_T, T_S, alpha, wrap_N)},
          {"method", "Sorge formulary (12a,b): xi_R = 2.2, xi_N = 1.5, n = 5, seat = pi/6, unseat = pi/18"}};
}

// Sorge–Cammalleri steady drive on the scene's two-pulley drive: S = c, drive-time constants from
// the paper's extrapolation τ_T ≈ 0.2/ω, τ_ε ≈ 0.3/ω, tensions F − ρAv² when the scene's
// `inertia` effect is on, else the static tensions F.
nlohmann::json viscoelastic_json(const belt::DriveCase& d, bool inertia) {
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
  in.belt.S_N = d.belt.c_N;
  in.belt.tau_T_s = 0.2 / in.omega_rad_s;
  in.belt.tau_eps_s = 0.3 / in.omega_rad_s;
  const double F_c =
      inertia ? d.belt.density_kg_m3 * d.belt.area_mm2 * d.belt_speed_mm_s * d.belt_speed_mm_s * 1e-12 : 0.0;
  in.slack_N = d.span_tension_N[drv] - F_c;
  in.tight_N = d.span_tension_N[1 - drv] - F_c;
  const auto sol = belt::solve_viscoelastic_drive(in);
  auto pulley = [](const belt::ViscoelasticPulley& p) {
    return nlohmann::json{{"entrance_sliding_deg", p.entrance_sliding_rad * 180 / kPi},
                          {"adhesion_deg", p.adhesion_rad * 180 / kPi},
                          {"main_sliding_deg", p.main_sliding_rad * 180 / kPi},
                          {"adhesion_elongation", p.adhesion_elongation},
                          {"max_relative_slip", p.max_relative_slip}};
  };
  return {{"model", "Sorge-Cammalleri three-parameter belt, tau_T = 0.2/omega, tau_eps = 0.3/omega"},
          {"S_N", in.belt.S_N}, {"tau_T_s", in.belt.tau_T_s}, {"tau_eps_s", in.belt.tau_eps_s},
          {"driver", pulley(sol.driver)}, {"driven", pulley(sol.driven)}};
}
}  // namespace

bool Plan::will_run(const std::string& effect) const {
  for (const auto& e : effects)
    if (e.name == effect) return e.reason.rfind("not", 0) != 0;
  return false;
}

Plan make_plan(const Scene& s) {
  Plan p;
  const bool history = flag(s.outputs, "load_history");
  const bool accumulation = flag(s.outputs, "strain_accumulation");
  const bool cvt = flag(s.outputs, "cvt_thrust");
  const bool tension_test = flag(s.outputs, "tension_test");
  const bool life = flag(s.outputs, "life");
  p.load_cycle_needed = history || life;
  p.accumulation = accumulation;
  p.cvt = cvt;
  p.tension_test = tension_test;
  p.viscoelastic = flag(s.effects, "viscoelastic_tension");
  // Reasons of effects that do not run start with "not" (Plan::will_run relies on it).
  auto add = [&](const std::string& name, bool run, const std::string& why,
                 const std::string& why_not = "not requested") {
    p.effects.push_back({name, false, 0.0, run ? why : why_not});
  };
  const std::string needed = history ? "needed by load_history" : "needed by life";
  const bool drive = p.load_cycle_needed || cvt || accumulation || p.viscoelastic || tension_test;
  add("stiffness", drive, "needed by the drive (belt c, k1, EI)");
  add("drive", drive, "geometry and span tensions, needed by the requested outputs");
  add("contact_arcs", p.load_cycle_needed, needed);
  for (const char* refinement : {"bending_zones", "inertia", "full_ode", "driver_exit_ramp"}) {
    const bool on = flag(s.effects, refinement);
    add(refinement, on && p.load_cycle_needed, std::string("[effects] ") + refinement + " = true",
        on ? "not run: no requested output uses the load cycle" : "not requested");
  }
  p.load_cycle.bending_zones = flag(s.effects, "bending_zones");
  p.load_cycle.inertia = flag(s.effects, "inertia");
  p.load_cycle.full_ode = flag(s.effects, "full_ode");
  p.load_cycle.driver_exit_ramp = flag(s.effects, "driver_exit_ramp");
  add("viscoelastic_tension", p.viscoelastic, "[effects] viscoelastic_tension = true");
  add("strain_accumulation", accumulation, "needed by strain_accumulation");
  add("cvt_thrust", cvt, "needed by cvt_thrust");
  add("tension_test", tension_test, "needed by tension_test");
  if (life) {
    p.unavailable_outputs.push_back("life");
    const std::string why = "not available in this version: segment FE and fatigue life come later";
    p.effects.push_back({"segment_fe", false, 0.0, why});
    p.effects.push_back({"fatigue", false, 0.0, why});
  }
  return p;
}

Stiffness resolve_stiffness(const Scene& s) {
  Stiffness k;
  const double T = s.temperature_C;
  auto card_for = [&](const char* role) -> std::optional<card::Card> {
    auto it = s.materials.find(role);
    if (it == s.materials.end()) return std::nullopt;
    return card::load_card(it->second);
  };
  const auto cord = s.c_N ? std::nullopt : card_for("cord");
  const auto bottom = (s.k1_MPa && s.EI_Nmm2) ? std::nullopt : card_for("bottom");
  if (s.c_N) {
    k.c_N = *s.c_N, k.c_source = "belt.stiffness.c_N";
  } else if (cord) {
    // Cord data at ε_a = 0.0025, 5 Hz (Report I §6.1): c = A_c E′.
    k.c_N = s.cord_area_mm2 * storage_modulus_MPa(*cord, "cord", "", 5.0, 0.0025, T);
    k.c_source = "card " + s.materials.at("cord") + " (A_c E', 5 Hz, 0.0025)";
  } else {
    k.c_N = belt::cord_stiffness_N(T, s.cord_area_mm2), k.c_source = "Fritzson (6.1), E1 = 100 MPa";
  }
  double E33 = 0.0;
  if (s.k1_MPa) {
    k.k1_MPa = *s.k1_MPa, k.k1_source = "belt.stiffness.k1_MPa";
  } else {
    if (bottom) {
      E33 = storage_modulus_MPa(*bottom, "bottom", "33", 34.0, 0.005, T);
      k.k1_source = "card " + s.materials.at("bottom") + " (E33', 34 Hz, 0.005) and (A.37)";
    } else {
      E33 = belt::axial_modulus_MPa(T);
      k.k1_source = "Fritzson (6.4), E0 = 10 MPa, and (A.37)";
    }
    k.k1_MPa = belt::radial_stiffness_MPa(s.belt.wedge_half_angle_rad, E33, s.belt.height_mm, s.belt.width_mm);
  }
  if (s.EI_Nmm2) {
    k.EI_Nmm2 = *s.EI_Nmm2, k.EI_source = "belt.stiffness.EI_Nmm2";
  } else if (bottom) {
    k.EI_Nmm2 = s.bending_inertia_mm4 * storage_modulus_MPa(*bottom, "bottom", "22", 34.0, 0.045, T);
    k.EI_source = "card " + s.materials.at("bottom") + " (I E22', 34 Hz, 0.045)";
  } else {
    k.EI_Nmm2 = belt::bending_stiffness_Nmm2(T) * s.bending_inertia_mm4 / belt::FritzsonConstants::bending_inertia_mm4;
    k.EI_source = "Fritzson (6.5), E0 = 10 MPa";
  }
  for (double v : {k.c_N, k.k1_MPa})
    if (!(v > 0.0) || !std::isfinite(v))
      throw InputError("belt stiffness from the material cards is not positive at " +
                           std::to_string(T) + " degC", s.path, 0, 0, "belt.materials");
  return k;
}

belt::DriveCase make_drive(const Scene& s, const Stiffness& k) {
  std::vector<belt::Pulley> pulleys;
  for (const auto& ps : s.pulleys) {
    belt::Pulley p;
    p.name = ps.name;
    p.pitch_radius_mm = ps.pitch_diameter_mm / 2.0;
    p.role = ps.role;
    p.torque_Nm = ps.torque_Nm;
    if (ps.center_mm) p.x_mm = ps.center_mm->first, p.y_mm = ps.center_mm->second;
    pulleys.push_back(p);
  }
  belt::DriveCase d;
  try {
    if (pulleys.size() == 2 && s.center_distance_mm) {
      const std::size_t drv = pulleys[1].role == belt::PulleyRole::driver ? 1 : 0;
      d.geometry = belt::make_two_pulley_geometry(pulleys[drv], pulleys[1 - drv], *s.center_distance_mm);
    } else {
      d.geometry = belt::make_geometry(pulleys);
    }
    const std::size_t di = belt::driver_index(d.geometry);
    const PulleySpec& driver = *std::find_if(s.pulleys.begin(), s.pulleys.end(), [&](const PulleySpec& p) {
      return p.name == d.geometry.pulleys[di].name;
    });
    const double R = d.geometry.pulleys[di].pitch_radius_mm;
    const double omega = driver.speed_rpm ? *driver.speed_rpm * 2.0 * kPi / 60.0 : 0.0;
    d.belt_speed_mm_s = omega * R;
    belt::TensionInput t;
    if (s.torque_Nm) t.driver_torque_Nm = *s.torque_Nm;
    if (s.power_kW) {
      if (!(omega > 0.0))
        throw InputError("power_kW needs the driver's speed_rpm", {}, 0, 0, "drive.power_kW");
      t.driver_torque_Nm = *s.power_kW * 1000.0 / omega;
    }
    t.rule = s.tension_rule;
    t.tension_N = s.tension_N;
    d.span_tension_N = belt::span_tensions(d.geometry, t);
  } catch (const InputError& e) {  // add the scene file to library errors
    throw InputError(e.detail(), s.path, 0, 0, e.key());
  }
  d.belt = s.belt;
  d.belt.c_N = k.c_N;
  d.belt.k1_MPa = k.k1_MPa;
  d.belt.EI_Nmm2 = k.EI_Nmm2;
  d.friction = s.friction;
  return d;
}

belt::RetardationSpectrum scene_spectrum(const Scene& s, const std::string& spec, std::string* source) {
  const std::string prefix = "material:";
  if (spec.rfind(prefix, 0) != 0) {
    if (source) *source = "shape " + spec;
    return belt::spectrum_shape(spec);
  }
  const std::string role = spec.substr(prefix.size());
  auto it = s.materials.find(role);
  if (it == s.materials.end())
    throw InputError("spectrum '" + spec + "' names no card under [belt.materials]", s.path, 0, 0,
                     "accumulation.spectrum");
  const card::Card c = card::load_card(it->second);
  const auto model = c.model();
  const auto values = c.values();
  belt::RetardationSpectrum r;  // the model's Kelvin series
  if (!model->kelvin_series(values.data(), &r))
    throw InputError("card " + it->second + " (model '" + c.model_kind +
                         "') has no discrete retardation spectrum J_g, L_i, lambda_i: fit a 'retardation' card",
                     s.path, 0, 0, "accumulation.spectrum");
  belt::validate(r, "accumulation.spectrum");
  if (source) *source = "card " + it->second + " (reference temperature)";
  return r;
}

double drive_kappa(const Scene& scene) {
  // Geometry only: the stiffness does not enter.
  const belt::DriveCase d = make_drive(scene, Stiffness{1.0, 1.0, 0.0, "", "", ""});
  const std::size_t i = belt::driver_index(d.geometry);
  return d.geometry.spans[i].center_distance_mm / d.geometry.pulleys[i].pitch_radius_mm;
}

AccumulationMap accumulation_map(const belt::RetardationSpectrum& s, const AccumulationSpec& a, double kappa) {
  AccumulationMap m;
  m.kappa = kappa;
  m.shear_stress_MPa = a.shear_stress_MPa;
  for (int i = 0; i < a.omega_points; ++i) {
    const double f = a.omega_points == 1 ? 0.0 : static_cast<double>(i) / (a.omega_points - 1);
    m.omega_rad_s.push_back(a.omega_min_rad_s * std::pow(a.omega_max_rad_s / a.omega_min_rad_s, f));
  }
  for (int j = 0; j < a.cycle_points; ++j) {
    const double f = a.cycle_points == 1 ? 1.0 : static_cast<double>(j) / (a.cycle_points - 1);
    const long N = std::lround(std::pow(static_cast<double>(a.cycles), f));
    if (m.cycles.empty() || N > m.cycles.back()) m.cycles.push_back(N);
  }
  for (double w : m.omega_rad_s) {
    for (long N : m.cycles) m.gamma.push_back(belt::accumulated_strain(s, a.shear_stress_MPa, N, w, kappa));
    if (a.strain_limit)
      m.critical_cycles.push_back(belt::critical_cycles(s, a.shear_stress_MPa, w, kappa, *a.strain_limit, a.cycles));
  }
  return m;
}

SceneResult run_scene(const Scene& s, const belt::LoadCycleOptions& options_in) {
  core::Stopwatch total;
  SceneResult r;
  r.plan = make_plan(s);
  auto timed = [&](const std::string& name, const std::function<void()>& f) {
    for (auto& e : r.plan.effects)
      if (e.name == name) {
        if (!r.plan.will_run(name)) return;
        core::Stopwatch w;
        f();
        e.wall_s = w.seconds();
        e.ran = true;
      }
  };
  std::optional<Stiffness> k;
  timed("stiffness", [&] { k = resolve_stiffness(s); });
  r.stiffness = k;
  timed("drive", [&] { r.drive = make_drive(s, *k); });
  belt::LoadCycleOptions options = options_in;
  options.effects = r.plan.load_cycle;
  // A load cycle takes well under a millisecond: time the best of three runs so the per-effect
  // costs (differences of such times) are not timer noise.
  auto best_of_three = [&](const belt::LoadCycleOptions& o, belt::LoadCycle& out) {
    double best = INFINITY;
    for (int k = 0; k < 3; ++k) {
      core::Stopwatch w;
      out = belt::compute_load_cycle(*r.drive, o);
      best = std::min(best, w.seconds());
    }
    return best;
  };
  double full_s = 0.0;
  timed("contact_arcs", [&] {
    r.cycle.emplace();
    full_s = best_of_three(options, *r.cycle);
  });
  for (auto& e : r.plan.effects)
    if (e.name == "contact_arcs" && e.ran) e.wall_s = full_s;
  if (r.cycle) {
    // Each refinement's cost and effect: the cycle again without it (accuracy versus time). The
    // refinement's time is the increment; contact_arcs reports the whole cycle, refinements included.
    for (auto& e : r.plan.effects) {
      belt::LoadCycleOptions without = options;
      bool* f = e.name == "bending_zones" ? &without.effects.bending_zones
                : e.name == "inertia" ? &without.effects.inertia
                : e.name == "full_ode" ? &without.effects.full_ode
                : e.name == "driver_exit_ramp" ? &without.effects.driver_exit_ramp : nullptr;
      if (!f || !r.plan.will_run(e.name)) continue;
      *f = false;
      belt::LoadCycle base;
      e.wall_s = std::max(0.0, full_s - best_of_three(without, base));
      e.ran = true;
      r.extra["effect_changes"][e.name] = {
          {"F_relative", relative_change(*r.cycle, base, &belt::LoadSample::F_N)},
          {"p_relative", relative_change(*r.cycle, base, &belt::LoadSample::p_MPa)},
          {"gamma_relative", relative_change(*r.cycle, base, &belt::LoadSample::gamma_rad)},
          {"K_relative", relative_change(*r.cycle, base, &belt::LoadSample::K_1_mm)},
          {"friction_used_relative", relative_change(*r.cycle, base, &belt::LoadSample::friction_used)}};
    }
  }
  timed("viscoelastic_tension", [&] { r.extra["viscoelastic_tension"] = viscoelastic_json(*r.drive, r.plan.load_cycle.inertia); });
  timed("strain_accumulation", [&] {
    const AccumulationSpec a = s.accumulation.value_or(AccumulationSpec{});
    std::string source;
    const auto spectrum = scene_spectrum(s, a.spectrum, &source);
    r.accumulation = accumulation_map(spectrum, a, a.kappa ? *a.kappa : drive_kappa(s));
    r.accumulation->spectrum_source = source;
  });
  timed("cvt_thrust", [&] {
    auto j = cvt_thrust_json(*r.drive, s.cvt.value_or(CvtSpec{}));
    if (r.cycle) {  // the 1-D thrust of the load cycle next to the formulary
      const auto& g = r.drive->geometry;
      const int drv = static_cast<int>(belt::driver_index(g));
      const int dvn = (drv + 1) % static_cast<int>(g.pulleys.size());
      j["load_cycle_driver_axial_thrust_N"] = belt::axial_thrust_N(*r.cycle, r.drive->belt, drv);
      j["load_cycle_driven_axial_thrust_N"] = belt::axial_thrust_N(*r.cycle, r.drive->belt, dvn);
    }
    r.extra["cvt_thrust"] = j;
  });
  timed("tension_test", [&] {
    const TensionTestSpec t = s.tension_test.value_or(TensionTestSpec{});
    const auto& g = r.drive->geometry;
    const std::size_t d = belt::driver_index(g);
    belt::TensionTestInput in;
    in.belt = {t.S_N.value_or(r.drive->belt.c_N), t.tau_T_s, t.tau_eps_s};
    in.d0_mm = g.spans[d].center_distance_mm;
    in.r_mm = g.pulleys[d].pitch_radius_mm;
    in.f = s.friction;
    in.v_mm_s = t.rate_mm_min / 60.0;
    in.load_time_s = t.load_time_s;
    in.nodes = t.nodes;
    in.steps_per_phase = t.steps;
    r.tension_test = belt::simulate_tension_test(in);
    const auto& u = r.tension_test->unloading.back();
    r.extra["tension_test"] = {{"peak_tension_N", r.tension_test->loading.back().span_tension_N},
                               {"end_of_unloading_tension_N", u.span_tension_N},
                               {"residual_elongation_mm", u.elongation_mm},
                               {"S_N", in.belt.S_N}, {"tau_T_s", in.belt.tau_T_s}, {"tau_eps_s", in.belt.tau_eps_s}};
  });
  r.total_wall_s = total.seconds();
  return r;
}

std::string load_history_csv(const SceneResult& r) {
  std::ostringstream o;
  o << std::setprecision(10);
  o << "s_mm,t_s,pulley,zone,F_N,K_1_per_mm,p_MPa,gamma_deg,sliding_velocity_mm_s,friction_used\n";
  if (!r.cycle) return o.str();
  const auto& names = r.drive->geometry.pulleys;
  for (const auto& x : r.cycle->samples)
    o << x.s_mm << ',' << x.t_s << ',' << names[x.pulley].name << ',' << belt::to_string(x.zone) << ','
      << x.F_N << ',' << x.K_1_mm << ',' << x.p_MPa << ',' << x.gamma_rad * 180.0 / kPi << ','
      << x.slide_mm_s << ',' << x.friction_used << '\n';
  return o.str();
}

std::string accumulation_csv(const AccumulationMap& m) {
  std::ostringstream o;
  o << std::setprecision(12);
  o << "omega_rad_s,cycles,accumulated_strain\n";
  for (std::size_t i = 0; i < m.omega_rad_s.size(); ++i)
    for (std::size_t j = 0; j < m.cycles.size(); ++j)
      o << m.omega_rad_s[i] << ',' << m.cycles[j] << ',' << m.gamma[i * m.cycles.size() + j] << '\n';
  return o.str();
}

std::string tension_test_csv(const belt::TensionTestResult& t) {
  std::ostringstream o;
  o << std::setprecision(10) << "phase,t_s,elongation_mm,span_tension_N,boundary_deg\n";
  for (const auto& [phase, pts] : {std::pair{"loading", &t.loading}, std::pair{"unloading", &t.unloading}})
    for (const auto& q : *pts)
      o << phase << ',' << q.t_s << ',' << q.elongation_mm << ',' << q.span_tension_N << ','
        << q.boundary_rad * 180.0 / kPi << '\n';
  return o.str();
}

nlohmann::json summary_json(const Scene& s, const SceneResult& r) {
  nlohmann::json j;
  j["scene"] = s.name;
  j["source"] = s.path;
  j["version"] = FITLIB_VERSION;
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : r.plan.effects)
    effects.push_back({{"name", e.name}, {"ran", e.ran}, {"wall_s", e.wall_s}, {"reason", e.reason}});
  j["effects"] = effects;
  j["outputs_not_available"] = r.plan.unavailable_outputs;
  j["total_wall_s"] = r.total_wall_s;
  if (r.stiffness)
    j["stiffness"] = {{"c_N", r.stiffness->c_N}, {"k1_MPa", r.stiffness->k1_MPa}, {"EI_Nmm2", r.stiffness->EI_Nmm2},
                      {"c_source", r.stiffness->c_source}, {"k1_source", r.stiffness->k1_source},
                      {"EI_source", r.stiffness->EI_source}};
  if (r.drive) {
    const auto& g = r.drive->geometry;
    j["drive"] = {{"belt_length_mm", g.belt_length_mm}, {"belt_speed_m_s", r.drive->belt_speed_mm_s / 1000.0},
                  {"friction", r.drive->friction}, {"temperature_C", s.temperature_C}};
    nlohmann::json spans = nlohmann::json::array();
    for (std::size_t i = 0; i < g.pulleys.size(); ++i)
      spans.push_back({{"from", g.pulleys[i].name}, {"to", g.pulleys[(i + 1) % g.pulleys.size()].name},
                       {"length_mm", g.spans[i].length_mm}, {"tension_N", r.drive->span_tension_N[i]}});
    j["drive"]["spans"] = spans;
  }
  if (r.cycle) {
    j["load_cycle"] = {{"centrifugal_tension_N", r.cycle->centrifugal_tension_N},
                       {"cycle_length_mm", r.cycle->cycle_length_mm}, {"cycle_time_s", r.cycle->cycle_time_s},
                       {"samples", r.cycle->samples.size()}};
    nlohmann::json pulleys = nlohmann::json::array();
    const double deg = 180.0 / kPi;
    for (const auto& p : r.cycle->pulleys) {
      double p_max = 0.0, gamma_max = 0.0;
      for (const auto& x : r.cycle->samples)
        if (r.drive->geometry.pulleys[x.pulley].name == p.name) {
          p_max = std::max(p_max, x.p_MPa);
          if (x.zone == belt::Zone::sliding) gamma_max = std::max(gamma_max, std::abs(x.gamma_rad - kPi));
        }
      pulleys.push_back({{"name", p.name}, {"role", belt::to_string(p.role)}, {"radius_mm", p.radius_mm},
                         {"wrap_deg", p.wrap_rad * deg}, {"F_in_N", p.F_in_N}, {"F_out_N", p.F_out_N},
                         {"c0", p.c0}, {"gamma_prime_P", p.gamma_prime_P},
                         {"contact_angle_in_deg", p.phi_C_in_rad * deg}, {"contact_angle_out_deg", p.phi_C_out_rad * deg},
                         {"entrance_zone_deg", p.phi_E_in_rad * deg}, {"exit_zone_deg", p.phi_E_out_rad * deg},
                         {"non_sliding_deg", p.non_sliding_rad * deg}, {"sliding_deg", p.sliding_rad * deg},
                         {"sliding_closed_form_deg", p.sliding_closed_form_rad >= 0 ? p.sliding_closed_form_rad * deg : -1.0},
                         {"sliding_ode_deg", p.sliding_ode_rad >= 0 ? p.sliding_ode_rad * deg : -1.0},
                         {"arc_method", p.arc_method}, {"capstan_limit", p.capstan_limit},
                         {"p_max_MPa", p_max}, {"sliding_angle_max_deviation_deg", gamma_max * deg}});
    }
    j["load_cycle"]["pulleys"] = pulleys;
  }
  if (r.accumulation) {
    const auto& m = *r.accumulation;
    j["strain_accumulation"] = {{"kappa", m.kappa}, {"shear_stress_MPa", m.shear_stress_MPa},
                                {"spectrum", m.spectrum_source}, {"omega_points", m.omega_rad_s.size()},
                                {"cycle_points", m.cycles.size()},
                                {"max_strain", m.gamma.empty() ? 0.0 : *std::max_element(m.gamma.begin(), m.gamma.end())}};
    if (!m.critical_cycles.empty()) {
      nlohmann::json area = nlohmann::json::array();
      for (std::size_t i = 0; i < m.omega_rad_s.size(); ++i)
        if (m.critical_cycles[i] > 0) area.push_back({{"omega_rad_s", m.omega_rad_s[i]}, {"critical_cycles", m.critical_cycles[i]}});
      j["strain_accumulation"]["critical_area"] = area;
    }
  }
  for (auto it = r.extra.begin(); it != r.extra.end(); ++it) j[it.key()] = it.value();
  return j;
}

std::vector<std::string> write_outputs(const Scene& s, const SceneResult& r, const std::string& dir) {
  std::filesystem::create_directories(dir);
  std::vector<std::string> written;
  auto put = [&](const std::string& name, const std::string& text) {
    const std::string path = (std::filesystem::path(dir) / name).string();
    core::write_file_atomically(path, text);
    written.push_back(path);
  };
  if (r.cycle && flag(s.outputs, "load_history")) put("load_history.csv", load_history_csv(r));
  if (r.accumulation) put("accumulation.csv", accumulation_csv(*r.accumulation));
  if (r.tension_test) put("tension_test.csv", tension_test_csv(*r.tension_test));
  put("summary.json", summary_json(s, r).dump(2) + "\n");
  return written;
}

}  // namespace fitlib::scene
