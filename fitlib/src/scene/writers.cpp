// Writers of a scene run: CSV tables, the JSON summary, life.json and the output folder.
#include "fitlib/fatigue/stress_csv.hpp"
#include "fitlib/scene/writers.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <set>
#include <sstream>

#include "fitlib/core/finite_output.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/segment/cycle.hpp"
#include "fitlib/scene/output_paths.hpp"

namespace fitlib::scene {
namespace {
using nlohmann::json;
using core::kPi;
constexpr double kDeg = 180.0 / kPi;

json stiffness_json(const Stiffness& k) {
  return {{"c_N", k.c_N}, {"k1_MPa", k.k1_MPa}, {"EI_Nmm2", k.EI_Nmm2}, {"c_source", k.c_source},
          {"k1_source", k.k1_source}, {"EI_source", k.EI_source}};
}

json drive_json(const Scene& s, const belt::DriveCase& d) {
  const auto& g = d.geometry;
  json j = {{"belt_length_mm", g.belt_length_mm}, {"belt_speed_m_s", d.belt_speed_mm_s / 1000.0},
            {"friction", d.friction}, {"temperature_C", s.temperature_C}};
  json spans = json::array();
  for (std::size_t i = 0; i < g.pulleys.size(); ++i)
    spans.push_back({{"from", g.pulleys[i].name}, {"to", g.pulleys[(i + 1) % g.pulleys.size()].name},
                     {"length_mm", g.spans[i].length_mm}, {"tension_N", d.span_tension_N[i]}});
  j["spans"] = spans;
  return j;
}

json pulley_json(const belt::PulleyCycle& p, const belt::LoadCycle& c, const belt::DriveCase& d) {
  double p_max = 0.0, gamma_max = 0.0;
  for (const auto& x : c.samples)
    if (d.geometry.pulleys[x.pulley].name == p.name) {
      p_max = std::max(p_max, x.p_MPa);
      if (x.zone == belt::Zone::sliding) gamma_max = std::max(gamma_max, std::abs(x.gamma_rad - kPi));
    }
  return {{"name", p.name}, {"role", belt::to_string(p.role)}, {"radius_mm", p.radius_mm},
          {"wrap_deg", p.wrap_rad * kDeg}, {"F_in_N", p.F_in_N}, {"F_out_N", p.F_out_N},
          {"c0", p.c0}, {"gamma_prime_P", p.gamma_prime_P},
          {"contact_angle_in_deg", p.phi_C_in_rad * kDeg}, {"contact_angle_out_deg", p.phi_C_out_rad * kDeg},
          {"entrance_zone_deg", p.phi_E_in_rad * kDeg}, {"exit_zone_deg", p.phi_E_out_rad * kDeg},
          {"non_sliding_deg", p.non_sliding_rad * kDeg}, {"sliding_deg", p.sliding_rad * kDeg},
          {"sliding_closed_form_deg", p.sliding_closed_form_rad >= 0 ? p.sliding_closed_form_rad * kDeg : -1.0},
          {"sliding_ode_deg", p.sliding_ode_rad >= 0 ? p.sliding_ode_rad * kDeg : -1.0},
          {"arc_method", p.arc_method}, {"capstan_limit", p.capstan_limit},
          {"p_max_MPa", p_max}, {"sliding_angle_max_deviation_deg", gamma_max * kDeg}};
}

json load_cycle_json(const belt::LoadCycle& c, const belt::DriveCase& d) {
  json j = {{"centrifugal_tension_N", c.centrifugal_tension_N}, {"cycle_length_mm", c.cycle_length_mm},
            {"cycle_time_s", c.cycle_time_s}, {"samples", c.samples.size()}};
  json pulleys = json::array();
  for (const auto& p : c.pulleys) pulleys.push_back(pulley_json(p, c, d));
  j["pulleys"] = pulleys;
  return j;
}

json accumulation_json(const AccumulationMap& m) {
  json j = {{"kappa", m.kappa}, {"shear_stress_MPa", m.shear_stress_MPa}, {"spectrum", m.spectrum_source},
            {"omega_points", m.omega_rad_s.size()}, {"cycle_points", m.cycles.size()},
            {"max_strain", m.gamma.empty() ? 0.0 : *std::max_element(m.gamma.begin(), m.gamma.end())}};
  if (!m.critical_cycles.empty()) {
    json area = json::array();
    for (std::size_t i = 0; i < m.omega_rad_s.size(); ++i)
      if (m.critical_cycles[i] > 0) area.push_back({{"omega_rad_s", m.omega_rad_s[i]}, {"critical_cycles", m.critical_cycles[i]}});
    j["critical_area"] = area;
  }
  return j;
}

json viscoelastic_json(const ViscoelasticTension& v) {
  auto pulley = [](const belt::ViscoelasticPulley& p) {
    return json{{"entrance_sliding_deg", p.entrance_sliding_rad * kDeg}, {"adhesion_deg", p.adhesion_rad * kDeg},
                {"main_sliding_deg", p.main_sliding_rad * kDeg}, {"adhesion_elongation", p.adhesion_elongation},
                {"max_relative_slip", p.max_relative_slip}};
  };
  return {{"model", "Sorge-Cammalleri three-parameter belt, S = c, drive-time constants tau_T = 0.2/omega, "
                    "tau_eps = 0.3/omega (belt::drive_time_belt)"},
          {"S_N", v.belt.S_N}, {"tau_T_s", v.belt.tau_T_s}, {"tau_eps_s", v.belt.tau_eps_s},
          {"driver", pulley(v.solution.driver)}, {"driven", pulley(v.solution.driven)}};
}

json cvt_json(const CvtThrust& t) {
  json j = {{"tight_tension_N", t.tight_tension_N}, {"slack_tension_N", t.slack_tension_N},
            {"groove_half_angle_deg", t.groove_half_angle_deg}, {"driver_wrap_deg", t.driver_wrap_rad * kDeg},
            {"driven_wrap_deg", t.driven_wrap_rad * kDeg}, {"driver_axial_thrust_N", t.driver_axial_thrust_N},
            {"driven_axial_thrust_N", t.driven_axial_thrust_N},
            {"method", "Sorge formulary (12a,b): xi_R = 2.2, xi_N = 1.5, n = 5, seat = pi/6, unseat = pi/18"}};
  if (t.load_cycle_driver_axial_thrust_N) j["load_cycle_driver_axial_thrust_N"] = *t.load_cycle_driver_axial_thrust_N;
  if (t.load_cycle_driven_axial_thrust_N) j["load_cycle_driven_axial_thrust_N"] = *t.load_cycle_driven_axial_thrust_N;
  return j;
}

json tension_test_json(const TensionTest& t) {
  const auto& u = t.result.unloading.back();
  return {{"peak_tension_N", t.result.loading.back().span_tension_N}, {"end_of_unloading_tension_N", u.span_tension_N},
          {"residual_elongation_mm", u.elongation_mm}, {"S_N", t.belt.S_N}, {"tau_T_s", t.belt.tau_T_s},
          {"tau_eps_s", t.belt.tau_eps_s}};
}

json effect_changes_json(const std::map<std::string, EffectChange>& changes) {
  json j = json::object();
  for (const auto& [name, c] : changes)
    j[name] = {{"F_relative", c.F}, {"p_relative", c.p}, {"gamma_relative", c.gamma}, {"K_relative", c.K},
               {"friction_used_relative", c.friction_used}};
  return j;
}

// The heat balance's fixed point (docs/thermal.md): temperature, each source and loss in W per belt.
json heat_json(const belt::BeltTemperature& h) {
  json layers = json::array();
  for (const belt::HysteresisLayer& l : h.sources.layers)
    layers.push_back({{"layer", l.name}, {"volume_mm3", l.volume_mm3}, {"loss_modulus_MPa", l.loss_modulus_MPa},
                      {"strain_amplitude", l.strain_amplitude}, {"work_per_cycle_J", belt::hysteresis_work_J(l)}});
  json j = {{"belt_temperature_C", h.temperature_C}, {"ambient_C", h.ambient_C}, {"pulley_C", h.paths.pulley_C},
          {"iterations", h.iterations}, {"hysteresis_W", h.sources.hysteresis_W},
          {"friction_W", h.sources.friction_W}, {"friction_to_belt", h.paths.friction_to_belt},
          {"heat_in_W", h.heat_in_W}, {"convection_W", h.convection_W}, {"contact_W", h.contact_W},
          {"convection_W_m2K", h.paths.convection_W_m2K}, {"air_area_m2", h.paths.air_area_m2},
          {"contact_W_m2K", h.paths.contact_W_m2K}, {"contact_area_m2", h.paths.contact_area_m2},
          {"balance_error", h.balance_error}, {"layers", layers}};
  if (h.segment_runs > 0) {  // the complete level: the segment's own dissipation (docs/thermal.md §1)
    const double out = h.convection_W + h.contact_W, in = h.segment_hysteresis_W + h.paths.friction_to_belt * h.sources.friction_W;
    j["segment"] = {{"runs", h.segment_runs}, {"over_layers", h.segment_over_layers},
                    {"layers_hysteresis_W", h.sources.hysteresis_W / h.segment_over_layers},
                    {"hysteresis_W", h.segment_hysteresis_W}, {"balance_error", std::abs(in - out) / in}};
  }
  return j;
}

std::string heat_text(const belt::BeltTemperature& h) {
  std::ostringstream o;
  o << "belt temperature: " << core::format_number(h.temperature_C, 4) << " degC from its heat balance (ambient "
    << core::format_number(h.ambient_C, 4) << ", pulleys " << core::format_number(h.paths.pulley_C, 4) << " degC; "
    << h.iterations << " fixed-point iterations)\n  heat in " << core::format_number(h.heat_in_W, 4)
    << " W per belt: hysteresis " << core::format_number(h.sources.hysteresis_W, 4) << " W, friction "
    << core::format_number(h.sources.friction_W, 4) << " W of which the belt takes "
    << core::format_number(100.0 * h.paths.friction_to_belt, 3) << " %\n  heat out: convection "
    << core::format_number(h.convection_W, 4) << " W (h " << core::format_number(h.paths.convection_W_m2K, 4)
    << " W/m2K), to the pulleys " << core::format_number(h.contact_W, 4) << " W\n";
  if (h.segment_runs > 0)
    o << "  hysteresis from the segment's own dissipation: " << core::format_number(h.segment_hysteresis_W, 4)
      << " W at the fixed point, " << core::format_number(h.segment_over_layers, 4) << " x the beam section's layers' "
      << core::format_number(h.sources.hysteresis_W / h.segment_over_layers, 4) << " W (" << h.segment_runs
      << " segment runs)\n";
  return o.str();
}

json card_reading_json(const CardReading& c) {
  json j = {{"role", c.role}, {"card", c.card}, {"temperature_C", c.temperature_C},
            {"frequency_Hz", c.frequency_Hz ? json(*c.frequency_Hz) : json(nullptr)},
            {"read_at_strain_amplitude", c.read_amplitude ? json(*c.read_amplitude) : json(nullptr)},
            {"reached_strain_amplitude", c.reached_amplitude},
            {"largest_tested_strain_amplitude", c.largest_tested_amplitude ? json(*c.largest_tested_amplitude) : json(nullptr)}};
  if (c.read_at) j["read_at_components"] = {{"e11", (*c.read_at)[0]}, {"e22", (*c.read_at)[1]}, {"g12", (*c.read_at)[2]}};
  if (c.read_range)  // [life] elastic_amplitude = "element"
    j["read_per_element"] = {{"elements", c.elements_read}, {"smallest_strain_amplitude", (*c.read_range)[0]},
                             {"largest_strain_amplitude", (*c.read_range)[1]}};
  if (const std::optional<double> f = c.beyond_tests_factor()) j["beyond_tests_factor"] = *f;
  return j;
}

// One line per card: where it was read and how far beyond its tests the segment drove it.
std::string card_reading_text(const CardReading& c) {
  std::ostringstream o;
  o << "card read: " << c.role << " " << c.card << " at " << core::format_number(c.temperature_C, 4) << " degC";
  if (c.frequency_Hz) o << ", " << core::format_number(*c.frequency_Hz, 4) << " Hz";
  if (c.read_range)
    o << ", each of its " << c.elements_read << " elements at its own strain amplitude, "
      << core::format_number((*c.read_range)[0], 3) << " to " << core::format_number((*c.read_range)[1], 3)
      << " (the largest: e11 " << core::format_number((*c.read_at)[0], 3) << ", e22 "
      << core::format_number((*c.read_at)[1], 3) << ", g12 " << core::format_number((*c.read_at)[2], 3) << ")";
  else if (c.read_at)
    o << ", strain amplitude " << core::format_number(*c.read_amplitude, 3) << " (e11 "
      << core::format_number((*c.read_at)[0], 3) << ", e22 " << core::format_number((*c.read_at)[1], 3) << ", g12 "
      << core::format_number((*c.read_at)[2], 3) << ")";
  else o << (c.frequency_Hz ? ", small amplitude" : ", the card's full model");
  o << "; the segment reached " << core::format_number(c.reached_amplitude, 3);
  if (c.largest_tested_amplitude) o << ", tests up to " << core::format_number(*c.largest_tested_amplitude, 3);
  if (const std::optional<double> f = c.beyond_tests_factor()) o << " (" << core::format_number(*f, 2) << "x beyond)";
  o << "\n";
  return o.str();
}

// stress_history.csv's points: the named ones and, of a design-region scan, the design points
// (the scan's other hundreds of points are read by the life, not written).
std::vector<fatigue::PointHistory> written_histories(const LifeResult& l, const std::vector<fatigue::PointHistory>& all) {
  std::vector<fatigue::PointHistory> out;
  for (const fatigue::PointHistory& p : all) {
    const bool design = std::any_of(l.report.modes.begin(), l.report.modes.end(),
                                    [&p](const fatigue::ModeLife& m) { return m.design_point == p.name; });
    if (p.element < 0 || design) out.push_back(p);
  }
  return out;
}

json life_summary_json(const LifeResult& l, bool effective_stress_history = false) {
  json j = fatigue::life_to_json(l.report, effective_stress_history);
  j["fidelity"] = core::to_string(l.plan.fidelity);
  j["fidelity_reason"] = l.plan.reason;
  json inputs = json::array();
  for (const auto& f : l.inputs)
    inputs.push_back({{"role", f.role}, {"path", f.path}, {"sha256", f.sha256}, {"used_for", f.used_for}});
  j["inputs"] = inputs;
  if (!l.distribution.empty()) j["distribution"] = fatigue::life_distribution_json(l.distribution);
  if (l.heat) j["heat_buildup"] = heat_json(*l.heat);
  if (l.equilibrium) {  // the segment's equilibrium check with its bounds (docs/formats.md §5)
    using B = segment::EquilibriumBounds;
    const SegmentEquilibrium& e = *l.equilibrium;
    j["segment_equilibrium"] = {{"equilibrium_error", e.equilibrium_error}, {"equilibrium_error_bound", B::equilibrium_error},
                                {"span_cord_share", e.span_cord_share}, {"span_cord_share_bound", e.span_cord_share_bound},
                                {"span_section_mismatch", e.span_section_mismatch},
                                {"span_section_mismatch_bound", B::span_section_mismatch},
                                {"span_increments", e.span_increments}, {"within_bounds", e.within_bounds()}};
  }
  if (const std::optional<SegmentRun>& w = l.segment_run)
    j["segment_run"] = {{"elements", w->elements}, {"cycles", w->cycles}, {"steps_per_cycle", w->steps_per_cycle},
                        {"conditioning_steps", w->conditioning_steps}, {"increments", w->increments},
                        {"newton_iterations", w->newton_iterations}, {"cuts", w->cuts}};
  if (!l.cards_read.empty()) {  // docs/fatigue.md §8 "The cards at the amplitude the segment drives them"
    json cards = json::array();
    for (const CardReading& c : l.cards_read) cards.push_back(card_reading_json(c));
    j["cards_read"] = cards;
    j["beyond_tests"] = l.beyond_tests;
  }
  if (const std::optional<AmplitudeIteration>& a = l.amplitude_iteration)
    j["amplitude_iteration"] = {{"runs", a->runs}, {"tolerance", a->tolerance}, {"changes", a->changes},
                                {"per", a->per}, {"relaxation", a->relaxation}, {"folded_runs", a->folded}};
  if (!l.fields.empty()) {  // full-field stress files (VTK) by name, so the bytes do not depend on the folder
    json fields = json::array();
    for (const FieldFile& f : l.fields)
      fields.push_back({{"at", f.at}, {"s_mm", f.s_mm}, {"file", std::filesystem::path(f.path).filename().string()}});
    j["fields"] = fields;
  }
  return j;
}

}  // namespace

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

std::string effects_table(const Plan& plan) {
  std::ostringstream o;
  for (const auto& e : plan.effects)
    o << "  " << (e.ran ? "ran     " : "not run ") << std::left << std::setw(21) << e.name << std::right
      << std::fixed << std::setprecision(3) << std::setw(10) << e.wall_s * 1e3 << " ms  (" << e.reason << ")\n";
  return o.str();
}

std::string life_text(const Scene& s, const SceneResult& r) {
  const LifeResult& l = r.life.value();
  std::ostringstream o;
  o << "scene: " << s.name << " (" << (l.heat ? l.heat->temperature_C : s.temperature_C) << " degC)\n"
    << "fidelity: " << core::to_string(l.plan.fidelity) << " (" << l.plan.reason << ")\n"
    << (l.heat ? heat_text(*l.heat) : "") << fatigue::life_table(l.report)
    << fatigue::life_distribution_table(l.report, l.distribution);
  if (l.equilibrium) {
    using B = segment::EquilibriumBounds;
    const SegmentEquilibrium& e = *l.equilibrium;
    const auto precision = o.precision();
    o << std::setprecision(2) << std::scientific << "segment equilibrium: error " << e.equilibrium_error << " (bound "
      << B::equilibrium_error << "), span cord-line share of F/B " << e.span_cord_share << " (bound "
      << e.span_cord_share_bound << "), span section mismatch " << e.span_section_mismatch << " (bound "
      << B::span_section_mismatch << ") over " << e.span_increments << " span increments\n"
      << std::defaultfloat << std::setprecision(static_cast<int>(precision));
    if (e.span_increments == 0) o << "note: no increment in a span, the span checks saw nothing\n";
    if (const std::optional<SegmentRun>& w = l.segment_run) {
      const std::string conditioning =
          w->conditioning_steps != w->steps_per_cycle ? " (" + std::to_string(w->conditioning_steps) + " in each before the last)" : "";
      o << "segment run: " << w->elements << " elements, " << w->cycles << " load cycle(s) of " << w->steps_per_cycle
        << " planned steps" << conditioning << ", " << w->increments << " increments, " << w->newton_iterations
        << " Newton iterations, " << w->cuts << " step cuts\n";
    }
    const bool default_mesh = !s.segment || !s.segment->life_mesh_changed;
    if (default_mesh && l.plan.fidelity == core::Fidelity::complete && l.damage_held)
      // docs/segment.md "Damage held beyond the tested amplitudes"
      o << "note: the complete level on the life's default segment (192 elements, 27 mm long, graded at the "
           "central gap, one cushion row, sheared end faces), with the cards' damage held at their tests' drivers, "
           "gives on the light, medium and heavy drives N1 0.76 to 1.01 x and N2 0.93 to 1.02 x those of 0.35 to "
           "0.6 mm elements with three cushion rows (N1 shorter, on the safe side, where it differs by more than 2 %; [segment] fine_size_mm = "
           "0.6 reads them at about 3 x the time; the heavy drive runs near its fold, where some finer meshes stop) (docs/segment.md "
           "\"Damage held beyond the tested amplitudes\")\n";
    else if (default_mesh && l.plan.fidelity == core::Fidelity::complete)  // docs/fatigue.md "Measured"
      o << "note: the complete level on the life's default segment (192 elements, 27 mm long, graded at the "
           "central gap, one cushion row, sheared end faces) gives on the light drive N1 0.82 x and N2 0.98 x "
           "those of 0.35 mm elements with three cushion rows (0.6 mm: 0.95 and 0.95 x) (docs/segment.md "
           "\"Which segment N1 should be read from\")\n";
    else if (default_mesh)  // measured accuracy of the life's default mesh (docs/fatigue.md "Measured (bench/bench_life)")
      o << "note: the life's default segment (192 elements, 27 mm long, graded at the central gap, one cushion "
           "row, sheared end faces) gives, against an 81 mm segment on the light, medium and heavy reference "
           "drives, the same governing mode and, with the thesis cards, N2 within 13 % (elastic level). Against "
           "the same segment with 0.35 mm elements and three cushion rows its N1 is 6 to 11 % shorter (on the "
           "safe side) and its N2 within 7 %; [segment] fine_size_mm = 0.35 and cushion_rows = 3 read them at "
           "about 11 x the time (docs/segment.md \"Stress at a point\")\n";
  }
  for (const CardReading& c : l.cards_read) o << card_reading_text(c);
  if (const std::optional<AmplitudeIteration>& a = l.amplitude_iteration)
    o << "elastic level: cards read at the amplitude the segment reached"
      << (a->per == "element" ? " by each element" : "") << ", " << a->runs << " runs, last change "
      << core::format_number(100.0 * a->changes.back(), 2) << " % (tolerance " << core::format_number(100.0 * a->tolerance, 2)
      << " %" << (a->per == "element" ? " of the role's largest element amplitude" : "")
      << (a->relaxation < 1.0 ? ", relaxed to " + core::format_number(a->relaxation, 2) : std::string())
      << (a->folded ? ", " + std::to_string(a->folded) + " folded and retried" : std::string()) << ")\n";
  if (!l.cards_read.empty()) o << "beyond the tests: [life] beyond_tests = \"" << l.beyond_tests << "\"\n";
  for (const std::string& w : r.warnings) o << "WARNING: " << w << "\n";
  for (const FieldFile& f : l.fields)
    o << "stress field at " << f.at << " (s = " << core::format_number(f.s_mm) << " mm, last cycle): " << f.path << "\n";
  o << "inputs:\n";
  for (const auto& f : l.inputs)
    o << "  " << std::left << std::setw(8) << f.role << std::right << f.path << "\n           sha256 " << f.sha256
      << ": " << f.used_for << "\n";
  return o.str();
}

json effects_json(const Plan& plan, bool wall_times) {
  json effects = json::array();
  for (const auto& e : plan.effects) {
    effects.push_back({{"name", e.name}, {"ran", e.ran}, {"reason", e.reason}, {"status", to_string(e.status)},
                       {"cost", e.cost}});
    if (wall_times) effects.back()["wall_s"] = e.wall_s;
  }
  return effects;
}

json summary_json(const Scene& s, const SceneResult& r, bool wall_times) {
  json j;
  j["scene"] = s.name;
  j["source"] = s.path;
  j["version"] = FITLIB_VERSION;
  j["effects"] = effects_json(r.plan, wall_times);
  j["outputs_not_available"] = r.plan.unavailable_outputs;
  if (wall_times) j["total_wall_s"] = r.total_wall_s;
  if (r.stiffness) j["stiffness"] = stiffness_json(*r.stiffness);
  if (r.drive) j["drive"] = drive_json(s, *r.drive);
  if (r.cycle) j["load_cycle"] = load_cycle_json(*r.cycle, *r.drive);
  if (!r.effect_changes.empty()) j["effect_changes"] = effect_changes_json(r.effect_changes);
  if (r.accumulation) j["strain_accumulation"] = accumulation_json(*r.accumulation);
  if (r.viscoelastic) j["viscoelastic_tension"] = viscoelastic_json(*r.viscoelastic);
  if (r.cvt) j["cvt_thrust"] = cvt_json(*r.cvt);
  if (r.tension_test) j["tension_test"] = tension_test_json(*r.tension_test);
  if (r.life) j["life"] = life_summary_json(*r.life);
  if (r.heat && !r.life) j["heat_buildup"] = heat_json(*r.heat);
  if (!r.warnings.empty()) j["warnings"] = r.warnings;
  return j;
}

json life_json(const Scene& s, const SceneResult& r, bool wall_times) {
  json j = life_summary_json(r.life.value(), true);  // summary.json stays a summary
  j["scene"] = s.name;
  j["source"] = s.path;
  j["version"] = FITLIB_VERSION;
  j["temperature_C"] = r.heat ? r.heat->temperature_C : s.temperature_C;  // the heat balance's when it ran
  j["effects"] = effects_json(r.plan, wall_times);
  if (wall_times) j["total_wall_s"] = r.total_wall_s;
  if (!r.warnings.empty()) j["warnings"] = r.warnings;
  return j;
}

std::vector<std::string> write_outputs(const Scene& s, const SceneResult& r, const std::string& dir,
                                       bool wall_times) {
  // Every file is made and checked finite before the first is written, so a NaN anywhere leaves
  // the folder as it was (NumericalError naming file, column or key, and row).
  std::vector<std::pair<std::string, std::string>> files;
  const auto csv = [&](const std::string& name, std::string text, const std::set<std::string>& labels) {
    core::require_finite_csv(text, name, labels);
    files.emplace_back(name, std::move(text));
  };
  const auto json_file = [&](const std::string& name, const json& j) {
    core::require_finite_json(j, name);
    files.emplace_back(name, j.dump(2) + "\n");
  };
  namespace f = folder_file;  // the names folder_outputs lists (output_paths.hpp)
  const auto history = s.outputs.find("load_history");
  if (r.cycle && history != s.outputs.end() && history->second)
    csv(f::load_history, load_history_csv(r), {"pulley", "zone"});
  if (r.accumulation) csv(f::accumulation, accumulation_csv(*r.accumulation), {});
  if (r.tension_test) csv(f::tension_test, tension_test_csv(r.tension_test->result), {"phase"});
  if (r.life && r.stresses)
    csv(f::stress_history, fatigue::stress_histories_csv(written_histories(*r.life, *r.stresses)), {"point", "role"});
  if (r.life) json_file(f::life, life_json(s, r, wall_times));
  json_file(f::summary, summary_json(s, r, wall_times));
  core::prepare_output_dir(dir);
  std::vector<std::string> written;
  for (const auto& [name, text] : files) {
    written.push_back((std::filesystem::path(dir) / name).string());
    core::write_file_atomically(written.back(), text);
  }
  return written;
}

}  // namespace fitlib::scene
