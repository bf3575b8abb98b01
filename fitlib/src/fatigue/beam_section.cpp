#include "fitlib/fatigue/beam_section.hpp"

#include <cmath>
#include <cstdio>

#include "fitlib/belt/stiffness.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::fatigue {

BeamSection default_beam_section(const belt::DriveCase& drive, double temperature_C) {
  BeamSection s;
  // The drive's own EI (from the bottom card's E22' when the scene has cards) over the 0.500 in
  // belt's 834 mm⁴; the Fritzson law (6.5) when the drive carries none.
  const double EI = drive.belt.EI_Nmm2 > 0.0 ? drive.belt.EI_Nmm2
                                             : belt::bending_stiffness_Nmm2(temperature_C);
  const double E = EI / belt::FritzsonConstants::bending_inertia_mm4;
  s.bottom_modulus_MPa = s.cushion_modulus_MPa = E;
  if (drive.geometry.belt_length_mm > 0.0)
    s.manufactured_curvature_1_mm = 2.0 * core::kPi / drive.geometry.belt_length_mm;
  return s;
}

namespace {

void check_section(const BeamSection& s) {
  auto bad = [](const std::string& key, const std::string& why) {
    throw core::InputError(why, "", 0, 0, "beam_section." + key);
  };
  if (!(s.cushion_mm > 0.0)) bad("cushion_mm", "must be positive");
  if (!(s.land_depth_mm > s.cushion_mm)) bad("land_depth_mm", "must be below the cushion");
  if (!(s.cog_depth_mm >= 0.0)) bad("cog_depth_mm", "must not be negative");
  if (!(s.cog_fill >= 0.0 && s.cog_fill <= 1.0)) bad("cog_fill", "must lie in [0, 1]");
  if (!(s.bottom_modulus_MPa > 0.0)) bad("bottom_modulus_MPa", "must be positive");
  if (!(s.cushion_modulus_MPa > 0.0)) bad("cushion_modulus_MPa", "must be positive");
  if (!(s.poisson > -1.0 && s.poisson < 0.5)) bad("poisson", "must lie in (-1, 0.5)");
  if (!(s.gap_stress_concentration > 0.0)) bad("gap_stress_concentration", "must be positive");
  if (!(s.manufactured_curvature_1_mm * s.land_depth_mm < 1.0))
    bad("manufactured_curvature_1_mm", "curvature radius must exceed the land depth");
  for (double d : s.bottom_depths_mm)
    if (!(d >= s.cushion_mm && d <= s.land_depth_mm))
      bad("bottom_depths_mm", "depth " + core::format_number(d) + " mm is not in the bottom layer");
  for (double d : s.cushion_depths_mm)
    if (!(d >= 0.0 && d <= s.cushion_mm))
      bad("cushion_depths_mm", "depth " + core::format_number(d) + " mm is not in the cushion");
}

struct Monitor {
  PointHistory history;
  double depth_mm, loaded_height_mm, modulus_MPa, concentration;
};

std::string depth_name(const char* prefix, double depth_mm) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s-%.3gmm", prefix, depth_mm);
  return buf;
}

std::vector<Monitor> monitors(const BeamSection& s) {
  std::vector<Monitor> out;
  const auto bottom = s.bottom_depths_mm.empty() ? std::vector<double>{s.land_depth_mm}
                                                 : s.bottom_depths_mm;
  const auto cushion = s.cushion_depths_mm.empty() ? std::vector<double>{0.5 * s.cushion_mm}
                                                   : s.cushion_depths_mm;
  for (double d : bottom)
    out.push_back({{depth_name("gap", d), Role::bottom, 0.0, -d, {}}, d,
                   s.land_depth_mm - d, s.bottom_modulus_MPa, s.gap_stress_concentration});
  for (double d : cushion)
    out.push_back({{depth_name("cushion", d), Role::cushion, 0.0, -d, {}}, d,
                   s.land_depth_mm - d + s.cog_fill * s.cog_depth_mm, s.cushion_modulus_MPa, 1.0});
  return out;
}

double running_speed_mm_s(const belt::DriveCase& drive) {
  if (!(drive.belt_speed_mm_s > 0.0))
    throw core::InputError("a life needs a running belt (belt speed > 0): a standing belt has no load cycle",
                           "", 0, 0, "drive.speed_rpm");
  return drive.belt_speed_mm_s;
}

}  // namespace

std::vector<PointHistory> beam_stress_histories(const belt::LoadCycle& cycle,
                                                const belt::DriveCase& drive,
                                                const BeamSection& s) {
  check_section(s);
  const double V = running_speed_mm_s(drive);
  const belt::BeltSection& b = drive.belt;
  const double beta = b.wedge_half_angle_rad, nu = s.poisson;
  const double rho_N_mm3 = b.density_kg_m3 * 1e-12;  // kg/m³ → N·s²/mm⁴
  std::vector<Monitor> ms = monitors(s);
  for (Monitor& m : ms) m.history.samples.reserve(cycle.samples.size());
  for (const belt::LoadSample& x : cycle.samples) {
    // Body forces of (6.6)–(6.7), per unit volume over B/2 per flank; only in a sheave.
    double B_r = 0.0, B_l = 0.0;
    if (x.p_MPa > 0.0) {
      const double bs = std::atan(std::tan(beta) * std::cos(x.gamma_rad));
      const double q = x.p_MPa * (2.0 / b.width_mm) / std::cos(beta);
      B_l = -x.friction_used * q * std::cos(bs) * std::sin(x.gamma_rad);
      B_r = q * (std::sin(beta) - x.friction_used * std::cos(bs) * std::cos(x.gamma_rad)) +
            rho_N_mm3 * x.K_1_mm * V * V;
    }
    const double eps_cord = x.F_N / b.c_N;
    for (Monitor& m : ms) {
      const double d = m.depth_mm;
      const double e22 = (1.0 + eps_cord) * (1.0 - x.K_1_mm * d) /
                             (1.0 - s.manufactured_curvature_1_mm * d) - 1.0;
      StressSample out;
      out.t_s = x.s_mm / V;
      out.s11_MPa = -B_r * m.loaded_height_mm;
      out.s12_MPa = B_l * m.loaded_height_mm;
      out.s22_MPa = m.concentration * m.modulus_MPa / (1.0 - nu * nu) * e22 +
                    nu / (1.0 - nu) * out.s11_MPa;
      m.history.samples.push_back(out);
    }
  }
  std::vector<PointHistory> out;
  for (Monitor& m : ms) out.push_back(std::move(m.history));
  return out;
}

LifeConditions cycle_conditions(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                                double temperature_C) {
  const double V = running_speed_mm_s(drive);
  LifeConditions c;
  c.temperature_C = temperature_C;
  c.cycle_time_s = 0.0;  // the load cycle is exactly one cycle
  if (cycle.cycle_length_mm > 0.0) c.cycles_per_hour = 3600.0 * V / cycle.cycle_length_mm;
  for (const belt::PulleyCycle& p : cycle.pulleys)
    c.pulleys.push_back({p.name, p.s_start_mm / V, p.s_end_mm / V});
  for (const belt::LoadSample& x : cycle.samples) c.cord_force_N.push_back(x.F_N);
  return c;
}

LifeReport beam_life(const belt::LoadCycle& cycle, const belt::DriveCase& drive,
                     const BeamSection& section, const FatigueCard& card, double temperature_C,
                     const PeakOptions& peaks) {
  const std::vector<PointHistory> points = beam_stress_histories(cycle, drive, section);
  LifeConditions c = cycle_conditions(cycle, drive, temperature_C);
  c.peaks = peaks;
  return evaluate_life(points, card, c);
}

}  // namespace fitlib::fatigue
