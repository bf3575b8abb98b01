// Heat sources and the steady lumped heat balance of the belt (heat.hpp, docs/thermal.md).
#include "fitlib/belt/heat.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"

namespace fitlib::belt {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

double hysteresis_work_J(const HysteresisLayer& l) {
  // MPa · mm³ = N·mm = 1e-3 J
  return kPi * l.loss_modulus_MPa * l.strain_amplitude * l.strain_amplitude * l.volume_mm3 * 1e-3;
}

double hysteresis_power_W(const std::vector<HysteresisLayer>& layers, double load_frequency_Hz) {
  double w = 0.0;
  for (const HysteresisLayer& l : layers) w += hysteresis_work_J(l);
  return w * load_frequency_Hz;
}

double loss_modulus_of_storage_MPa(double storage_MPa, double loss_angle_deg) {
  return storage_MPa * std::tan(loss_angle_deg * kPi / 180.0);
}

double adiabatic_heating_rate_C_s(double loss_modulus_MPa, double strain_amplitude, double frequency_Hz,
                                  double specific_heat_J_kgC, double density_kg_m3) {
  return kPi * strain_amplitude * strain_amplitude * loss_modulus_MPa * 1e6 * frequency_Hz /
         (specific_heat_J_kgC * density_kg_m3);
}

double friction_power_W(const LoadCycle& cycle, const BeltSection& belt, int pulley) {
  // Trapezoidal rule along s of 2 flanks × p H/cos β × μ_u × v_slide (MPa·mm·mm/s = 1e-3 W per mm).
  const double flank_mm = belt.height_mm / std::cos(belt.wedge_half_angle_rad);
  double sum = 0.0;
  for (std::size_t k = 1; k < cycle.samples.size(); ++k) {
    const LoadSample &a = cycle.samples[k - 1], &b = cycle.samples[k];
    if (pulley >= 0 && (a.pulley != pulley || b.pulley != pulley)) continue;
    const double qa = a.p_MPa * a.friction_used * std::abs(a.slide_mm_s);
    const double qb = b.p_MPa * b.friction_used * std::abs(b.slide_mm_s);
    sum += 0.5 * (qa + qb) * (b.s_mm - a.s_mm);
  }
  return 2.0 * flank_mm * sum * 1e-3;
}

double friction_power_W(const LoadCycle& cycle, const BeltSection& belt) { return friction_power_W(cycle, belt, -1); }

AirProperties air_at(double film_C) {
  // Incropera & DeWitt Table A.4 (1 atm): T (K), k (W/m K), ν (m²/s), Pr.
  static const double rows[4][4] = {{250.0, 22.3e-3, 11.44e-6, 0.720},
                                    {300.0, 26.3e-3, 15.89e-6, 0.707},
                                    {350.0, 30.0e-3, 20.92e-6, 0.700},
                                    {400.0, 33.8e-3, 26.41e-6, 0.690}};
  const double T = std::clamp(film_C + 273.15, 250.0, 400.0);
  int i = 0;
  while (i < 2 && T > rows[i + 1][0]) ++i;
  const double w = (T - rows[i][0]) / (rows[i + 1][0] - rows[i][0]);
  auto lerp = [&](int c) { return rows[i][c] + w * (rows[i + 1][c] - rows[i][c]); };
  return {lerp(1), lerp(2), lerp(3)};
}

double flat_plate_convection_W_m2K(double speed_m_s, double length_m, const AirProperties& air) {
  const double re = speed_m_s * length_m / air.kinematic_viscosity_m2_s;
  const double pr3 = std::cbrt(air.prandtl);
  const double nu = re <= 5e5 ? 0.664 * std::sqrt(re) * pr3 : (0.037 * std::pow(re, 0.8) - 871.0) * pr3;
  return nu * air.conductivity_W_mK / length_m;
}

HeatPaths heat_paths(const DriveCase& drive, const ThermalOptions& o, double belt_C) {
  HeatPaths h;
  const BeltSection& b = drive.belt;
  const double flank_m = b.height_mm / std::cos(b.wedge_half_angle_rad) * 1e-3, width_m = b.width_mm * 1e-3;
  const double speed_m_s = drive.belt_speed_mm_s * 1e-3, length_m = drive.geometry.belt_length_mm * 1e-3;
  h.pulley_C = std::isnan(o.pulley_C) ? o.ambient_C : o.pulley_C;
  // The bulk-to-surface path: the mean of a parabolic profile lies (B/2)/3 inside the flank.
  const double bulk_W_m2K = o.rubber_conductivity_W_mK / (width_m / 6.0);
  const double density = b.density_kg_m3;
  const double rubber_effusivity = std::sqrt(o.rubber_conductivity_W_mK * density * o.specific_heat_J_kgC);
  h.friction_to_belt = std::isnan(o.friction_to_belt) ? rubber_effusivity / (rubber_effusivity + o.pulley_effusivity)
                                                      : o.friction_to_belt;
  double contact_length_m = 0.0, spans_m = 0.0;
  const auto& g = drive.geometry;
  for (std::size_t j = 0; j < g.pulleys.size(); ++j) {
    const double arc_m = g.pulleys[j].pitch_radius_mm * g.wrap_rad[j] * 1e-3;
    contact_length_m += arc_m;
    spans_m += g.spans[j].length_mm * 1e-3;
    // Carslaw & Jaeger: a semi-infinite solid whose surface is held at the pulley's temperature for
    // the contact time t_c takes 2 e ΔT √(t_c/π) per area: h = 2 e/√(π t_c) over the contact.
    const double t_c = arc_m / speed_m_s;
    const double pen = 2.0 * rubber_effusivity / std::sqrt(kPi * t_c);
    const double h_c = std::isnan(o.contact_W_m2K) ? 1.0 / (1.0 / pen + 1.0 / bulk_W_m2K) : o.contact_W_m2K;
    h.contact_area_m2.push_back(2.0 * flank_m * arc_m);
    h.contact_W_m2K.push_back(h_c);
    h.contact_W_K.push_back(h_c * h.contact_area_m2.back());
  }
  // Top and bottom over the whole length, the flanks over the spans (the cogs' extra area is not counted).
  h.air_area_m2 = 2.0 * width_m * length_m + 2.0 * flank_m * (length_m - contact_length_m);
  const double mean_span_m = spans_m / static_cast<double>(g.spans.size());
  const double film_C = 0.5 * (belt_C + o.ambient_C);
  h.convection_W_m2K = std::isnan(o.convection_W_m2K)
                           ? 1.0 / (1.0 / flat_plate_convection_W_m2K(speed_m_s, mean_span_m, air_at(film_C)) +
                                    1.0 / bulk_W_m2K)
                           : o.convection_W_m2K;
  h.convection_W_K = h.convection_W_m2K * h.air_area_m2;
  return h;
}

namespace {

// The temperature at which the losses at `paths` carry `in` away, and the losses at T.
double balance_temperature(const HeatPaths& p, double ambient_C, double in) {
  double G = p.convection_W_K, GT = p.convection_W_K * ambient_C;
  for (double g : p.contact_W_K) G += g, GT += g * p.pulley_C;
  return (in + GT) / G;
}

void fill_losses(BeltTemperature& t) {
  t.convection_W = t.paths.convection_W_K * (t.temperature_C - t.ambient_C);
  t.contact_W = 0.0;
  for (double g : t.paths.contact_W_K) t.contact_W += g * (t.temperature_C - t.paths.pulley_C);
  const double out = t.convection_W + t.contact_W;
  t.balance_error = std::abs(t.heat_in_W - out) / std::max(std::abs(t.heat_in_W), 1e-300);
}

[[noreturn]] void runaway(const std::string& why) {
  throw core::NumericalError("thermal runaway: " + why +
                             " (docs/thermal.md §4: the heat the belt makes grows faster with its temperature than "
                             "the losses; a real failure mode, or a card read far beyond its data window)");
}

}  // namespace

BeltTemperature solve_belt_temperature(const DriveCase& drive, const ThermalOptions& o,
                                       const std::function<HeatSources(double)>& sources) {
  BeltTemperature t;
  t.ambient_C = o.ambient_C;
  double T = o.ambient_C, relax = 1.0, last_step = HUGE_VAL;
  for (int k = 1; k <= o.max_iterations; ++k) {
    t.sources = sources(T);
    t.paths = heat_paths(drive, o, T);
    t.heat_in_W = t.sources.hysteresis_W + t.paths.friction_to_belt * t.sources.friction_W;
    const double target = balance_temperature(t.paths, o.ambient_C, t.heat_in_W);
    if (!std::isfinite(target) || target > o.max_temperature_C)
      runaway("iteration " + std::to_string(k) + " asks for " + core::short_number(target) + " degC, beyond " +
              core::short_number(o.max_temperature_C) + " degC");
    const double step = target - T;
    t.iterations = k;
    if (std::abs(step) <= o.tolerance_C) {
      t.temperature_C = target;
      fill_losses(t);
      return t;
    }
    if (std::abs(step) >= last_step) relax *= 0.5;  // an oscillating fixed point: damp it
    last_step = std::abs(step);
    T += relax * step;
  }
  runaway("the fixed point did not settle in " + std::to_string(o.max_iterations) + " iterations (last step " +
          core::short_number(last_step) + " degC)");
}

}  // namespace fitlib::belt
