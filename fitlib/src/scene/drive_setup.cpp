// What a scene's drive is made of: the belt's stiffnesses (cards, overrides or the Fritzson
// laws), the drive case, κ, and the retardation spectrum and map of strain accumulation.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "fitlib/belt/stiffness.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/model.hpp"
#include "fitlib/scene/planner.hpp"
#include "effects.hpp"

namespace fitlib::scene {
namespace {
using core::InputError;
using core::kPi;

// A shear card without a bulk modulus answers by the conversion eval and export use (K from its
// instantaneous modulus and [belt.materials] poisson_ratio).
double storage_modulus_MPa(const Scene& s, const card::Card& c, const std::string& role, const char* orientation,
                           double f_Hz, double amplitude, std::vector<std::string>& warnings) {
  try {
    const auto model = c.model();
    model::TestCondition tc;
    tc.mode = model::TestMode::uniaxial;
    tc.orientation = orientation;
    tc.frequency_Hz = f_Hz;
    tc.temperature_C = s.temperature_C;
    tc.strain_amplitude = amplitude;
    detail::card_window_warnings(s, role, c, tc, warnings);
    return card::moduli_in_mode(*model, c.values(), tc, s.material_poisson_ratio).storage;
  } catch (const std::exception& e) {  // e.g. a shear card that is not a Prony-type series
    throw InputError(std::string("card cannot give the uniaxial storage modulus the belt needs: ") + e.what(),
                     {}, 0, 0, "belt.materials." + role);
  }
}

}  // namespace

void detail::card_window_warnings(const Scene& s, const std::string& role, const card::Card& c,
                                  const model::TestCondition& at, std::vector<std::string>& warnings) {
  if (const std::string q = card::fit_quality_warning(c); !q.empty()) {  // once per card and role
    const std::string w = "card " + s.materials.at(role) + " (" + role + "): " + q;
    if (std::find(warnings.begin(), warnings.end(), w) == warnings.end()) warnings.push_back(w);
  }
  for (const card::WindowExcess& e : card::outside_data_window(c, at)) {
    // One warning per card, role and quantity: the values the scene read it at, as a range.
    const std::string head = "card " + s.materials.at(role) + " (" + role + "): " + e.quantity + " ";
    const std::string tail = " its data window [" + core::format_number(e.low, 4) + ", " +
                             core::format_number(e.high, 4) + "] (fit.data_window." + e.key +
                             "): the scene extrapolates the card there";
    double lo = e.value, hi = e.value;
    const auto same = std::find_if(warnings.begin(), warnings.end(), [&](const std::string& w) {
      return w.rfind(head, 0) == 0 && w.size() > tail.size() && w.compare(w.size() - tail.size(), tail.size(), tail) == 0;
    });
    if (same != warnings.end()) {  // "<lo> is outside" or "<lo> … <hi> reach beyond"
      const std::string values = same->substr(head.size());
      lo = std::min(lo, std::stod(values));
      const auto dots = values.find(" … ");
      hi = std::max(hi, dots == std::string::npos ? std::stod(values) : std::stod(values.substr(dots + 5)));
    }
    const std::string w = head + core::format_number(lo, 4) +
                          (lo == hi ? " is outside" : " … " + core::format_number(hi, 4) + " reach beyond") + tail;
    if (same != warnings.end()) *same = w;
    else warnings.push_back(w);
  }
}

// A stiffness must be positive; `key` is where its value came from (an override, a card's role, or
// the scene's temperature for a Fritzson law).
static void require_positive(const Scene& s, const char* name, double value, const std::string& source,
                             const std::string& key) {
  if (value > 0.0 && std::isfinite(value)) return;
  throw InputError(std::string("belt stiffness ") + name + " = " + core::format_number(value) + " is not positive at " +
                       core::format_number(s.temperature_C) + " degC (from " + source + ")",
                   s.path, 0, 0, key);
}

card::Card detail::material_card(const Scene& s, const std::string& role) {
  const std::string& path = s.materials.at(role);
  card::Card c = card::load_card(path);
  if (const auto drawn = s.card_values.find(role); drawn != s.card_values.end())
    for (std::size_t i = 0; i < c.parameters.size() && i < drawn->second.size(); ++i)
      c.parameters[i].value = drawn->second[i];
  card::require_material_at(c, path, s.temperature_C, s.path, "conditions.temperature_C");
  return c;
}

Stiffness resolve_stiffness(const Scene& s) {
  Stiffness k;
  const double T = s.temperature_C;
  auto card_for = [&](const char* role) -> std::optional<card::Card> {
    if (!s.materials.count(role)) return std::nullopt;
    return detail::material_card(s, role);
  };
  const auto cord = s.c_N ? std::nullopt : card_for("cord");
  const auto bottom = (s.k1_MPa && s.EI_Nmm2) ? std::nullopt : card_for("bottom");
  // Cord data at ε_a = 0.0025, 5 Hz (Report I §6.1): c = A_c E′.
  std::tie(k.c_N, k.c_source) =
      s.c_N ? std::make_pair(*s.c_N, std::string("belt.stiffness.c_N"))
      : cord ? std::make_pair(s.cord_area_mm2 * storage_modulus_MPa(s, *cord, "cord", "", 5.0, 0.0025, k.warnings),
                              "card " + s.materials.at("cord") + " (A_c E', 5 Hz, 0.0025)")
             : std::make_pair(belt::cord_stiffness_N(T, s.cord_area_mm2), std::string("Fritzson (6.1), E1 = 100 MPa"));
  double E33 = 0.0;
  if (s.k1_MPa) {
    k.k1_MPa = *s.k1_MPa, k.k1_source = "belt.stiffness.k1_MPa";
  } else {
    if (bottom) {
      E33 = storage_modulus_MPa(s, *bottom, "bottom", "33", 34.0, 0.005, k.warnings);
      k.k1_source = "card " + s.materials.at("bottom") + " (E33', 34 Hz, 0.005) and (A.37)";
    } else {
      E33 = belt::axial_modulus_MPa(T);
      k.k1_source = "Fritzson (6.4), E0 = 10 MPa, and (A.37)";
    }
    k.k1_MPa = belt::radial_stiffness_MPa(s.belt.wedge_half_angle_rad, E33, s.belt.height_mm, s.belt.width_mm);
  }
  std::tie(k.EI_Nmm2, k.EI_source) =
      s.EI_Nmm2 ? std::make_pair(*s.EI_Nmm2, std::string("belt.stiffness.EI_Nmm2"))
      : bottom  ? std::make_pair(s.bending_inertia_mm4 * storage_modulus_MPa(s, *bottom, "bottom", "22", 34.0, 0.045, k.warnings),
                                 "card " + s.materials.at("bottom") + " (I E22', 34 Hz, 0.045)")
                : std::make_pair(belt::bending_stiffness_Nmm2(T) * s.bending_inertia_mm4 /
                                     belt::FritzsonConstants::bending_inertia_mm4,
                                 std::string("Fritzson (6.5), E0 = 10 MPa"));
  const auto key = [&](bool given, const char* given_key, bool card, const char* role) {
    return given ? std::string(given_key) : card ? std::string("belt.materials.") + role : std::string("conditions.temperature_C");
  };
  require_positive(s, "c", k.c_N, k.c_source, key(s.c_N.has_value(), "belt.stiffness.c_N", cord.has_value(), "cord"));
  require_positive(s, "k1", k.k1_MPa, k.k1_source,
                   key(s.k1_MPa.has_value(), "belt.stiffness.k1_MPa", bottom.has_value(), "bottom"));
  using F = belt::FritzsonConstants;
  // The Fritzson laws this scene uses, and the card or key that would replace each.
  const bool law_c = !s.c_N && !cord, law_k1 = !s.k1_MPa && !bottom, law_EI = !s.EI_Nmm2 && !bottom;
  std::string laws, remedy;
  for (const auto& [used, law] : {std::pair{law_c, "(6.1) c"}, std::pair{law_k1, "(6.4) E33"}, std::pair{law_EI, "(6.5) EI"}})
    if (used) laws += (laws.empty() ? "" : ", ") + std::string(law);
  if (law_c) remedy = "a cord card under [belt.materials] (or belt.stiffness.c_N)";
  if (law_k1 || law_EI)
    remedy += (remedy.empty() ? "" : " and ") + std::string("a bottom card under [belt.materials] (or belt.stiffness.") +
              (law_k1 && law_EI ? "k1_MPa and EI_Nmm2)" : law_k1 ? "k1_MPa)" : "EI_Nmm2)");
  if (!laws.empty() && (T < F::tested_low_C || T > F::tested_high_C))
    k.warnings.push_back("the Fritzson stiffness laws " + laws + " are straight lines through tests from " +
                         core::format_number(F::tested_low_C) + " to about " + core::format_number(F::tested_high_C) +
                         " degC; at " + core::format_number(T) + " degC they are extrapolated" +
                         (laws.find("(6.4)") != std::string::npos ? " (E33 of (6.4) is zero at 115.8 degC)" : "") +
                         "; give " + remedy);
  return k;
}

// [belt] length_mm is not an input of the drive (the pulleys and their centres give the cord
// line's length): a given value must agree with it, so that a user's length is never ignored.
static void check_given_belt_length(const Scene& s, const belt::DriveGeometry& g) {
  const auto it = s.extra_geometry_mm.find("length_mm");
  if (it == s.extra_geometry_mm.end()) return;
  const double L = g.belt_length_mm, given = it->second;
  if (std::abs(given - L) <= 0.01 * L) return;
  throw InputError("length_mm = " + core::format_number(given) + " differs by " +
                       core::format_number(100.0 * (given - L) / L, 3) +
                       " % from the belt (pitch, cord-line) length the pulleys and centre distance give, " +
                       core::format_number(L, 6) + " mm: correct the centre distance or remove length_mm",
                   s.path, 0, 0, "belt.length_mm");
}

belt::DriveCase make_drive(const Scene& s, const Stiffness& k) {
  if (s.pulleys.empty())
    throw InputError("missing [drive] table: the scene has only a [segment] static case (fitcli segment); the belt "
                     "drive, its load cycle and its life need the drive",
                     s.path, 0, 0, "drive");
  std::vector<belt::Pulley> pulleys;
  for (const auto& ps : s.pulleys) {
    if (!(ps.pitch_diameter_mm / 2.0 > s.belt.height_mm))  // the belt wraps every pulley with its bottom inside
      throw InputError("pitch diameter " + core::format_number(ps.pitch_diameter_mm) +
                           " mm: a pitch radius at or below the belt's height (" + core::format_number(s.belt.height_mm) +
                           " mm) puts the belt's bottom at or beyond the pulley's centre",
                       s.path, 0, 0, "drive.pulleys[" + std::to_string(pulleys.size()) + "].pitch_diameter_mm");
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
    check_given_belt_length(s, d.geometry);
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
    d.tension_key = belt::tension_key(t.rule);
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
    throw InputError("the strain accumulation reads the retardation spectrum of the '" + role + "' card (" + spec +
                         (spec == AccumulationSpec{}.spectrum ? ", the default" : "") + "), and card " + it->second +
                         " (model '" + c.model_kind + "') has no discrete spectrum J_g, L_i, lambda_i: fit a "
                         "'retardation' card for that role, or set [accumulation] spectrum to a shape (gauss, box, "
                         "lorentzian, ramp, wedge)",
                     s.path, 0, 0, "accumulation.spectrum");
  belt::validate(r, "accumulation.spectrum");
  if (source) *source = "card " + it->second + " (reference temperature)";
  return r;
}

double drive_kappa(const Scene& scene) {
  // Geometry only: the stiffness does not enter.
  const belt::DriveCase d = make_drive(scene, Stiffness{1.0, 1.0, 0.0, "", "", "", {}});
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

}  // namespace fitlib::scene
