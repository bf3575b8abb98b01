#include "fitlib/fatigue/beam_section.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fitlib/belt/stiffness.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/quadrature.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::fatigue {

double layer_stretch(double cord_strain, double K_1_mm, double K_m_1_mm, double depth_mm) {
  return (1.0 + cord_strain) * (1.0 - K_1_mm * depth_mm) / (1.0 - K_m_1_mm * depth_mm) - 1.0;
}

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
  if (!(s.pitch_mm >= 0.0)) bad("pitch_mm", "must not be negative");
  if (!(s.manufactured_curvature_1_mm * s.land_depth_mm < 1.0))
    bad("manufactured_curvature_1_mm", "curvature radius must exceed the land depth");
  for (double d : s.bottom_depths_mm)
    if (!(d >= s.cushion_mm && d <= s.land_depth_mm))
      bad("bottom_depths_mm", "depth " + core::format_number(d) + " mm is not in the bottom layer");
  for (double d : s.cushion_depths_mm)
    if (!(d >= 0.0 && d <= s.cushion_mm))
      bad("cushion_depths_mm", "depth " + core::format_number(d) + " mm is not in the cushion");
}

// Jourawski's shear of a beam whose bending changes along the path (a sheave's entrance and exit):
// equilibrium along the belt, ∂σ22/∂s + ∂σ12/∂y + B_l = 0 with σ12 = 0 on the free bottom, gives
// σ12 = ∫ (B_l + ∂σ22/∂s) w dy over the rubber below the point (w = 1 in the land, the cog fill in the
// cogs; σ22 = E/(1 − ν²) ε22 of each layer). With PitchSample's ∂ε22/∂s (below), the ∂σ22/∂s part is
// Δε/p · I0 − ΔM/p · I1, I0 = ∫ w E′/(1 − K_m d) dd and I1 = ∫ w E′ d/(1 − K_m d) dd (3-point
// Gauss–Legendre per layer).
struct DepthIntegrals {
  double I0 = 0.0, I1 = 0.0;
};

DepthIntegrals bending_shear_integrals(const BeamSection& s, double depth_mm, bool over_cogs) {
  DepthIntegrals out;
  auto layer = [&](double d0, double d1, double E, double w) {
    if (!(d1 > d0)) return;
    for (const core::QuadraturePoint& q : core::gauss_legendre_3(d0, d1)) {
      const double weight = q.weight * w * E / (1.0 - s.poisson * s.poisson) /
                            (1.0 - s.manufactured_curvature_1_mm * q.x);
      out.I0 += weight, out.I1 += weight * q.x;
    }
  };
  const double land = s.land_depth_mm, below_cushion = std::max(depth_mm, s.cushion_mm);
  layer(depth_mm, below_cushion, s.cushion_modulus_MPa, 1.0);
  layer(below_cushion, land, s.bottom_modulus_MPa, 1.0);
  if (over_cogs) layer(land, land + s.cog_depth_mm, s.bottom_modulus_MPa, s.cog_fill);
  return out;
}

struct Monitor {
  PointHistory history;
  double depth_mm, loaded_height_mm, modulus_MPa, concentration;
  DepthIntegrals bending;  // of the rubber below it: to the free land (gap), or with the cogs (cushion)
};

// A named point on the section's centre line (element −1: not a scanned FE point).
PointHistory named_point(const char* prefix, Role role, double depth_mm) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s-%.3gmm", prefix, depth_mm);
  PointHistory p;
  p.name = buf, p.role = role, p.y_mm = -depth_mm;
  return p;
}

std::vector<Monitor> monitors(const BeamSection& s) {
  std::vector<Monitor> out;
  const auto bottom = s.bottom_depths_mm.empty() ? std::vector<double>{s.land_depth_mm}
                                                 : s.bottom_depths_mm;
  const auto cushion = s.cushion_depths_mm.empty() ? std::vector<double>{0.5 * s.cushion_mm}
                                                   : s.cushion_depths_mm;
  for (double d : bottom)
    out.push_back({named_point("gap", Role::bottom, d), d,
                   s.land_depth_mm - d, s.bottom_modulus_MPa, s.gap_stress_concentration,
                   bending_shear_integrals(s, d, false)});
  for (double d : cushion)
    out.push_back({named_point("cushion", Role::cushion, d), d,
                   s.land_depth_mm - d + s.cog_fill * s.cog_depth_mm, s.cushion_modulus_MPa, 1.0,
                   bending_shear_integrals(s, d, true)});
  return out;
}

double running_speed_mm_s(const belt::DriveCase& drive) {
  if (!(drive.belt_speed_mm_s > 0.0))
    throw core::InputError("a life needs a running belt (belt speed > 0): a standing belt has no load cycle",
                           "", 0, 0, "drive.speed_rpm");
  return drive.belt_speed_mm_s;
}

struct BodyForce {
  double radial = 0.0, longitudinal = 0.0;  // B_r, B_l (N/mm³)
};

// Body forces of (6.6)–(6.7) at one sample, per unit volume over B/2 per flank; only in a sheave.
BodyForce body_force(const belt::LoadSample& x, const belt::BeltSection& b, double V_mm_s) {
  if (!(x.p_MPa > 0.0)) return {};
  const double beta = b.wedge_half_angle_rad;
  const double rho_N_mm3 = b.density_kg_m3 * 1e-12;  // kg/m³ → N·s²/mm⁴
  const double bs = std::atan(std::tan(beta) * std::cos(x.gamma_rad));
  const double q = x.p_MPa * (2.0 / b.width_mm) / std::cos(beta);
  return {q * (std::sin(beta) - x.friction_used * std::cos(bs) * std::cos(x.gamma_rad)) +
              rho_N_mm3 * x.K_1_mm * V_mm_s * V_mm_s,
          -x.friction_used * q * std::cos(bs) * std::sin(x.gamma_rad)};
}

// A periodic, piecewise-linear f(s) through the cycle's samples (closed from the last sample back
// to the first one period on): its value anywhere and its exact mean over an interval, through the
// running integral G(s).
class PathSeries {
 public:
  PathSeries(std::vector<double> s_mm, std::vector<double> f, double period_mm)
      : s_(std::move(s_mm)), f_(std::move(f)), L_(period_mm), G_(s_.size() + 1, 0.0) {
    s_.push_back(s_.front() + L_), f_.push_back(f_.front());
    for (std::size_t i = 0; i + 1 < s_.size(); ++i)
      G_[i + 1] = G_[i] + 0.5 * (f_[i] + f_[i + 1]) * (s_[i + 1] - s_[i]);
  }
  double at(double s) const { return piece(s).value; }
  double mean(double centre_mm, double w_mm) const {
    return (piece(centre_mm + 0.5 * w_mm).integral - piece(centre_mm - 0.5 * w_mm).integral) / w_mm;
  }

 private:
  struct Piece {
    double value, integral;  // f(s) and G(s) − G(s_0), one period adding G(L)
  };
  Piece piece(double s) const {
    const double turns = std::floor((s - s_.front()) / L_);
    const double r = s - turns * L_;
    std::size_t i = std::upper_bound(s_.begin(), s_.end(), r) - s_.begin();
    i = std::min(std::max<std::size_t>(i, 1), s_.size() - 1) - 1;
    const double h = s_[i + 1] - s_[i], t = r - s_[i];
    const double slope = h > 0.0 ? (f_[i + 1] - f_[i]) / h : 0.0;
    return {f_[i] + slope * t, turns * G_.back() + G_[i] + f_[i] * t + 0.5 * slope * t * t};
  }
  std::vector<double> s_, f_;
  double L_;
  std::vector<double> G_;
};

// What a point's pitch gathers at one sample: the body forces' mean over the pitch centred on it,
// and the pitch-mean of ∂ε22/∂s at depth d, (Δε − d ΔM)/(pitch (1 − K_m d)) with ε = F/c, M = (1 + ε) K
// and Δ their change across the pitch (ε22 of the layer stretch above).
struct PitchSample {
  BodyForce force;
  double d_strain_ds = 0.0, d_bend_ds = 0.0;  // Δε/pitch, ΔM/pitch (1/mm, 1/mm²)
};

std::vector<PitchSample> pitch_samples(const belt::LoadCycle& cycle, const belt::DriveCase& drive, double pitch_mm,
                                       double V_mm_s) {
  std::vector<double> path, radial, longitudinal, strain, bend;
  for (const belt::LoadSample& x : cycle.samples) {
    const BodyForce b = body_force(x, drive.belt, V_mm_s);
    path.push_back(x.s_mm), radial.push_back(b.radial), longitudinal.push_back(b.longitudinal);
    strain.push_back(x.F_N / drive.belt.c_N), bend.push_back((1.0 + strain.back()) * x.K_1_mm);
  }
  const double L = cycle.cycle_length_mm;
  const PathSeries Br(path, radial, L), Bl(path, longitudinal, L), e(path, strain, L), M(path, bend, L);
  std::vector<PitchSample> out;
  for (double s : path) {
    const double ahead = s + 0.5 * pitch_mm, behind = s - 0.5 * pitch_mm;
    out.push_back({{Br.mean(s, pitch_mm), Bl.mean(s, pitch_mm)},
                   (e.at(ahead) - e.at(behind)) / pitch_mm, (M.at(ahead) - M.at(behind)) / pitch_mm});
  }
  return out;
}

}  // namespace

std::vector<PointHistory> beam_stress_histories(const belt::LoadCycle& cycle,
                                                const belt::DriveCase& drive,
                                                const BeamSection& s) {
  check_section(s);
  const double V = running_speed_mm_s(drive);
  const belt::BeltSection& b = drive.belt;
  const double nu = s.poisson;
  const bool over_pitch = s.pitch_mm > 0.0 && cycle.samples.size() >= 2 &&
                          cycle.cycle_length_mm >= cycle.samples.back().s_mm - cycle.samples.front().s_mm;
  const std::vector<PitchSample> pitch = over_pitch ? pitch_samples(cycle, drive, s.pitch_mm, V) : std::vector<PitchSample>{};
  std::vector<Monitor> ms = monitors(s);
  for (Monitor& m : ms) m.history.samples.reserve(cycle.samples.size());
  for (std::size_t k = 0; k < cycle.samples.size(); ++k) {
    const belt::LoadSample& x = cycle.samples[k];
    const BodyForce f = over_pitch ? pitch[k].force : body_force(x, b, V);
    for (Monitor& m : ms) {
      StressSample out;
      out.t_s = x.s_mm / V;
      out.s11_MPa = -f.radial * m.loaded_height_mm;
      out.s12_MPa = f.longitudinal * m.loaded_height_mm;
      if (over_pitch)
        out.s12_MPa += pitch[k].d_strain_ds * m.bending.I0 - pitch[k].d_bend_ds * m.bending.I1;
      const double e22 = layer_stretch(x.F_N / b.c_N, x.K_1_mm, s.manufactured_curvature_1_mm, m.depth_mm);
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
