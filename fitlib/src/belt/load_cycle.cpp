#include "fitlib/belt/load_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {
namespace {
using core::InputError;
using core::kPi;

// Curvature polynomial of an entrance/exit zone and its integrals (4.21–4.34).
struct ZonePolynomial {
  double A1, A2, K0C;
  double A3() const { return 1.0 - A1 - A2; }
  double K0(double psi) const {
    return K0C + (1.0 - K0C) * (A1 * psi + A2 * psi * psi + A3() * psi * psi * psi);
  }
  double P(double psi) const {  // ∫(1 − K0)/(1 − K0C) dψ up to sign: the bracket of (4.27)
    return -psi + A1 * psi * psi / 2 + A2 * std::pow(psi, 3) / 3 + A3() * std::pow(psi, 4) / 4;
  }
  double X(double psi) const {  // ∫P dψ: the bracket of (4.28) without A4ψ + A5
    return -psi * psi / 2 + A1 * std::pow(psi, 3) / 6 + A2 * std::pow(psi, 4) / 12 +
           A3() * std::pow(psi, 5) / 20;
  }
};
const ZonePolynomial kEntrance{ZoneConstants::A1_in, ZoneConstants::A2_in, ZoneConstants::K0C_in};
const ZonePolynomial kExit{ZoneConstants::A1_out, ZoneConstants::A2_out, ZoneConstants::K0C_out};

// Free-span curvature (4.9) at distance u from the span middle; contact at u_C with curvature
// K_C. Written with exponentials so that a vanishing EI (λ → ∞) does not overflow.
double free_span_curvature(double K_C, double lambda, double u, double u_C) {
  if (!std::isfinite(lambda)) return 0.0;  // no bending stiffness: straight up to the contact point
  const double e = std::exp(-lambda * (u_C - u));
  return K_C * e * (1.0 + std::exp(-2.0 * lambda * u)) / (1.0 + std::exp(-2.0 * lambda * u_C));
}

// Samples a zone [s0, s1) (the end point only when `last`).
void sample_zone(double s0, double s1, const LoadCycleOptions& o, bool last,
                 const std::function<void(double)>& at) {
  if (s1 <= s0) return;
  const int n = std::max(o.min_samples_per_zone, static_cast<int>(std::ceil((s1 - s0) / o.step_mm)));
  for (int k = 0; k < n + (last ? 1 : 0); ++k) at(s0 + (s1 - s0) * k / n);
}
}  // namespace

const char* to_string(Zone z) {
  switch (z) {
    case Zone::free_span_in: return "free_span_in";
    case Zone::entrance: return "entrance";
    case Zone::non_sliding: return "non_sliding";
    case Zone::sliding: return "sliding";
    case Zone::exit: return "exit";
    case Zone::free_span_out: return "free_span_out";
  }
  return "?";
}

double side_pressure_MPa(double effective_force_N, double radius_mm, const BeltSection& belt,
                         double friction, double gamma_rad) {
  const double beta = belt.wedge_half_angle_rad;
  const double bs = std::atan(std::tan(beta) * std::cos(gamma_rad));
  return effective_force_N * std::cos(beta) /
         (2.0 * belt.height_mm * radius_mm *
          (std::sin(beta) - friction * std::cos(bs) * std::cos(gamma_rad)));
}

namespace {

void check_belt_and_speed(const BeltSection& belt, double V) {
  if (!(belt.height_mm > 0 && belt.width_mm > 0 && belt.area_mm2 > 0))
    throw InputError("belt height, width and area must be positive", {}, 0, 0, "belt.height_mm");
  if (!(belt.c_N > 0)) throw InputError("longitudinal stiffness c must be positive", {}, 0, 0, "belt.stiffness.c_N");
  if (!(belt.k1_MPa > 0)) throw InputError("radial stiffness k1 must be positive", {}, 0, 0, "belt.stiffness.k1_MPa");
  if (!(belt.EI_Nmm2 >= 0)) throw InputError("bending stiffness EI must be >= 0", {}, 0, 0, "belt.stiffness.EI_Nmm2");
  if (!(V >= 0) || !std::isfinite(V)) throw InputError("belt speed must be >= 0", {}, 0, 0, "drive.pulleys");
}

// Every span must stay under tension once the centrifugal tension F_c is taken off.
void check_span_tensions(const DriveCase& drive, double F_c) {
  const auto& g = drive.geometry;
  for (std::size_t i = 0; i < g.pulleys.size(); ++i) {
    const double F = drive.span_tension_N[i];
    if (F - F_c > 0.0) continue;
    const bool lifts = F_c > 0.0 && F > 0.0;
    throw InputError(lifts ? "centrifugal tension " + core::format_number(F_c, 4) + " N exceeds the tension " +
                                 core::format_number(F, 4) + " N of the span leaving '" + g.pulleys[i].name +
                                 "': the belt lifts off"
                           : "span leaving '" + g.pulleys[i].name +
                                 "' has no tension: the belt does not press on the pulleys",
                     {}, 0, 0, lifts ? "drive.pulleys" : drive.tension_key);
  }
}

// Free-span contact angles (4.13) and zone lengths (4.37 with φ_Eref = s0FB − s0FC of the
// reference case, i.e. Eq 4.12 continued until K0 = 1; decisions.md). Returns the contact arc
// left for the non-sliding and sliding arcs; InputError when the zones take the whole wrap.
double set_zone_angles(PulleyCycle& pc, const BeltSection& belt, bool bend, double Fe_in, double Fe_out,
                       const std::string& key) {
  const double R = pc.radius_mm;
  auto root_EI0_over_F0 = [&](double Fe) { return std::sqrt(belt.EI_Nmm2 / Fe) / R; };
  if (bend) {
    pc.phi_C_in_rad = std::atan(root_EI0_over_F0(Fe_in) * ZoneConstants::K0C_in);
    pc.phi_C_out_rad = std::atan(root_EI0_over_F0(Fe_out) * ZoneConstants::K0C_out);
    pc.phi_E_in_rad = root_EI0_over_F0(Fe_in) * std::log(1.0 / ZoneConstants::K0C_in);
    pc.phi_E_out_rad = root_EI0_over_F0(Fe_out) * std::log(1.0 / ZoneConstants::K0C_out);
  }
  const double alpha = pc.wrap_rad;
  const double contact_free = alpha - pc.phi_C_in_rad - pc.phi_C_out_rad - pc.phi_E_in_rad - pc.phi_E_out_rad;
  if (!(contact_free > 0.0))
    throw InputError("wrap angle " + core::format_number(alpha * 180 / kPi) + " deg of pulley '" + pc.name +
                         "' is smaller than its entrance and exit zones (" +
                         core::format_number((alpha - contact_free) * 180 / kPi) + " deg): the belt does not seat",
                     {}, 0, 0, key);
  return contact_free;
}

// The sliding arc of a pulley (Appendix A): the closed form, or the ODE when asked or when the
// closed form is out of range; identity (κ = 1) for an idler or equal tensions.
struct SlidingArc {
  std::unique_ptr<ClosedFormArc> closed;
  OdeArc ode;
  bool use_ode = false;
  double sinking_at_P = 0.0;  // f_P
  ArcPoint at(double phi) const {
    return use_ode ? interpolate(ode, phi) : closed ? closed->at(phi) : ArcPoint{phi, 1.0, kPi, sinking_at_P};
  }
};

SlidingArc solve_sliding_arc(PulleyCycle& pc, const ArcParameters& ap, double kappa_end, double contact_free,
                             const LoadCycleOptions& o, const std::string& key) {
  SlidingArc arc;
  arc.sinking_at_P = sinking_ratio_at_P(ap);
  const bool slides = pc.role != PulleyRole::idler && std::abs(kappa_end - 1.0) > 1e-12;
  if (!slides) {
    pc.arc_method = "none";
    return arc;
  }
  if (pc.role == PulleyRole::driver ? kappa_end > 1.0 : kappa_end < 1.0)
    throw InputError("pulley '" + pc.name + "' (" + to_string(pc.role) + ") would need the belt force to " +
                         (kappa_end > 1.0 ? "rise" : "fall") + " over it: check roles and torques",
                     {}, 0, 0, key + ".role");
  pc.gamma_prime_P = sliding_angle_slope_at_P(ap);
  arc.closed = std::make_unique<ClosedFormArc>(ap);
  pc.sliding_closed_form_rad = arc.closed->sliding_arc_length(kappa_end);
  arc.use_ode = o.effects.full_ode || pc.sliding_closed_form_rad < 0.0;
  if (arc.use_ode) {
    arc.ode = integrate_sliding_arc(ap, kappa_end, contact_free, o.ode_tolerance);
    pc.sliding_ode_rad = arc.ode.reached_kappa_end ? arc.ode.phi_end_rad : -1.0;
    pc.sliding_rad = pc.sliding_ode_rad;
    pc.arc_method = o.effects.full_ode ? "ode" : "ode (closed form out of range)";
  } else {
    pc.sliding_rad = pc.sliding_closed_form_rad;
    pc.arc_method = "closed-form";
  }
  if (!(pc.sliding_rad >= 0.0) || pc.sliding_rad > contact_free)
    throw InputError("belt slips on pulley '" + pc.name + "': the tension ratio " +
                         core::format_number(std::max(kappa_end, 1.0 / kappa_end), 4) +
                         " needs a longer sliding arc than the " + core::format_number(contact_free * 180 / kPi, 4) +
                         " deg of contact available (the capstan limit exp(mu alpha/sin beta) = " +
                         core::format_number(pc.capstan_limit, 4) +
                         " holds for a radially rigid belt only: with c0 = " + core::format_number(ap.c0, 3) +
                         " the belt also slides radially in the groove as its force changes, and that part of the "
                         "friction does not change the force, Appendix A); " +
                         (ap.friction > 0.0 ? "lower the torque or raise the tension"
                                            : "without friction (conditions.friction = 0) no torque is carried"),
                     {}, 0, 0, "drive.torque_Nm");
  return arc;
}

// Zone boundaries of one pulley (4.15–4.17, 4.18) from its start, a = tangent span lengths.
struct ZoneBounds {
  double s_Cin, s_Ein, s_NS, s_Eout, s_Cout, sL;
};

ZoneBounds zone_bounds(PulleyCycle& pc, double a_in, double a_out, double s_offset) {
  const double R = pc.radius_mm;
  ZoneBounds z;
  z.sL = 0.5 * (a_in + a_out) + pc.wrap_rad * R;
  z.s_Cin = 0.5 * a_in + pc.phi_C_in_rad * R;
  z.s_Ein = z.s_Cin + pc.phi_E_in_rad * R;
  z.s_Cout = z.sL - 0.5 * a_out - pc.phi_C_out_rad * R;
  z.s_Eout = z.s_Cout - pc.phi_E_out_rad * R;
  z.s_NS = z.s_Eout - pc.sliding_rad * R;
  pc.s_start_mm = s_offset;
  pc.s_Cin_mm = s_offset + z.s_Cin;
  pc.s_Ein_mm = s_offset + z.s_Ein;
  pc.s_NS_mm = s_offset + z.s_NS;
  pc.s_Eout_mm = s_offset + z.s_Eout;
  pc.s_Cout_mm = s_offset + z.s_Cout;
  pc.s_end_mm = s_offset + z.sL;
  return z;
}

// Samples the six zones of one pulley into the load cycle.
struct PulleySampler {
  const DriveCase& drive;
  const LoadCycleOptions& o;
  const PulleyCycle& pc;
  const SlidingArc& arc;
  const ZoneBounds& z;
  int index;
  double s_offset, F_c, Fe_in, Fe_out;
  bool bend;
  LoadCycle& out;

  double R() const { return pc.radius_mm; }
  double mu() const { return drive.friction; }
  double V() const { return drive.belt_speed_mm_s; }

  void push(double s_local, Zone zone, double F, double K, double p, double gamma, double slide,
            double friction_used) const {
    LoadSample x;
    x.s_mm = s_offset + s_local;
    x.t_s = V() > 0.0 ? x.s_mm / V() : 0.0;
    x.pulley = index;
    x.zone = zone;
    x.F_N = F;
    x.K_1_mm = K;
    x.p_MPa = std::max(p, 0.0);
    x.gamma_rad = gamma;
    x.slide_mm_s = slide;
    x.friction_used = friction_used;
    out.samples.push_back(x);
  }

  void all(bool last) const {
    const double p_in = side_pressure_MPa(Fe_in, R(), drive.belt, mu(), kPi);
    free_span_in();
    if (bend) entrance(p_in);
    sample_zone(z.s_Ein, z.s_NS, o, false,
                [&](double s) { push(s, Zone::non_sliding, pc.F_in_N, 1.0 / R(), p_in, kPi, 0.0, mu()); });
    sliding();
    if (bend) exit_zone();
    free_span_out(last);
  }

  // 1 free span, entrance side.
  void free_span_in() const {
    const double lambda = bend ? std::sqrt(Fe_in / drive.belt.EI_Nmm2) : INFINITY;
    const double K0C = bend ? ZoneConstants::K0C_in : 1.0;
    sample_zone(0.0, z.s_Cin, o, false, [&](double s) {
      push(s, Zone::free_span_in, pc.F_in_N, free_span_curvature(K0C / R(), lambda, s, z.s_Cin), 0, 0, 0, 0);
    });
  }

  // 2 entrance zone: γ = 180°, θ_E = −0.000418, x0C = 0 (A5 = 0, 4.40), p ∝ x0 (4.48).
  void entrance(double p_in) const {
    const double phiE = pc.phi_E_in_rad, one_m = 1.0 - kEntrance.K0C;
    const double A4 = -ZoneConstants::theta_E_in / (phiE * one_m) - kEntrance.P(1.0);
    auto x0 = [&](double psi) { return phiE * phiE * one_m * (kEntrance.X(psi) + A4 * psi); };
    const double x0E = x0(1.0);
    sample_zone(z.s_Cin, z.s_Ein, o, false, [&](double s) {
      const double psi = (s - z.s_Cin) / (z.s_Ein - z.s_Cin);
      const double theta = -phiE * one_m * (kEntrance.P(psi) + A4);
      push(s, Zone::entrance, pc.F_in_N, kEntrance.K0(psi) / R(), p_in * x0(psi) / x0E, kPi, V() * std::abs(theta),
           mu());
    });
  }

  // 4 sliding arc (4.18): φ = (s − s_NS)/R.
  void sliding() const {
    const double F0P = Fe_in / (R() * R() * drive.belt.k1_MPa);
    sample_zone(z.s_NS, z.s_Eout, o, false, [&](double s) {
      const ArcPoint a = arc.at((s - z.s_NS) / R());
      const double Fe = a.kappa * Fe_in;
      // Circumferential slip (A.20): (x0 − x0P) + (ε − εP); v_s sin γ equals it (A.5).
      const double circ = F0P * ((a.x0_over_F0P - arc.sinking_at_P) + (a.kappa - 1.0) / pc.c0);
      const double sg = std::sin(a.gamma_rad);
      push(s, Zone::sliding, Fe + F_c, 1.0 / R(), side_pressure_MPa(Fe, R(), drive.belt, mu(), a.gamma_rad),
           a.gamma_rad, std::abs(sg) > 1e-12 ? V() * std::abs(circ / sg) : 0.0, mu());
    });
  }

  // 5 exit zone: θ_Eout from the exit sliding angle (4.47) with γ_NC = 1° (driven), 359° (driver).
  void exit_zone() const {
    const ArcPoint arc_end = arc.at(pc.sliding_rad);
    const double p_Eout = side_pressure_MPa(arc_end.kappa * Fe_in, R(), drive.belt, mu(), arc_end.gamma_rad);
    const double phiE = pc.phi_E_out_rad, one_m = 1.0 - kExit.K0C;
    const double gamma_NE = arc_end.gamma_rad;
    const double gamma_NC = (pc.role == PulleyRole::driver ? 359.0 : 1.0) * kPi / 180.0;
    const double D = -kExit.P(1.0) * phiE * one_m;
    const double den = std::tan(gamma_NE) - std::tan(gamma_NC);
    const double theta_E = std::abs(den) > 1e-12 ? std::tan(gamma_NC) * D / den : 0.0;
    auto shape = [&](double thetaE, double psi) {
      const double A4 = thetaE / (phiE * one_m) - kExit.P(1.0);
      return phiE * phiE * one_m * (kExit.X(psi) + A4 * psi);
    };
    // p ∝ x0 (4.49); if θ_E makes x0 at the zone start non-positive, the pressure shape uses θ_E = 0.
    const double thetaE_p = shape(theta_E, 1.0) > 0.0 ? theta_E : 0.0;
    const double x0E = shape(thetaE_p, 1.0);
    const double sgn = theta_E < 0.0 ? -1.0 : 1.0;
    const double circ = theta_E * std::tan(gamma_NE);  // θ tan γ = const (4.46)
    const double ramp = o.exit_ramp_fraction;
    sample_zone(z.s_Eout, z.s_Cout, o, false, [&](double s) {
      const double psi = (z.s_Cout - s) / (z.s_Cout - z.s_Eout);
      const double theta = theta_E + phiE * one_m * (kExit.P(psi) - kExit.P(1.0));
      double gamma_N = std::atan2(sgn * theta_E * std::sin(gamma_NE), sgn * theta * std::cos(gamma_NE));
      if (gamma_N < 0.0) gamma_N += 2.0 * kPi;
      double used = mu();
      if (o.effects.driver_exit_ramp && pc.role == PulleyRole::driver && 1.0 - psi < ramp)
        used = mu() * 0.5 * (1.0 + std::cos(2.0 * kPi * (1.0 - psi) / ramp));  // full → 0 → full
      push(s, Zone::exit, pc.F_out_N, kExit.K0(psi) / R(), p_Eout * shape(thetaE_p, psi) / x0E, gamma_N,
           V() * std::hypot(circ, theta), used);
    });
  }

  // 6 free span, exit side.
  void free_span_out(bool last) const {
    const double lambda = bend ? std::sqrt(Fe_out / drive.belt.EI_Nmm2) : INFINITY;
    const double K0C = bend ? ZoneConstants::K0C_out : 1.0;
    sample_zone(z.s_Cout, z.sL, o, last, [&](double s) {
      push(s, Zone::free_span_out, pc.F_out_N, free_span_curvature(K0C / R(), lambda, z.sL - s, z.sL - z.s_Cout), 0,
           0, 0, 0);
    });
  }
};

}  // namespace

LoadCycle compute_load_cycle(const DriveCase& drive, const LoadCycleOptions& o) {
  const DriveGeometry& g = drive.geometry;
  const BeltSection& belt = drive.belt;
  const std::size_t n = g.pulleys.size();
  const double mu = drive.friction, V = drive.belt_speed_mm_s;
  if (drive.span_tension_N.size() != n)
    throw core::UsageError("compute_load_cycle: one span tension per pulley expected");
  check_belt_and_speed(belt, V);

  LoadCycle out;
  // Centrifugal tension (4.53): ρ [kg/m³]·A [mm²]·V² [mm²/s²] · 1e-12 → N.
  const double F_c = o.effects.inertia ? belt.density_kg_m3 * belt.area_mm2 * V * V * 1e-12 : 0.0;
  out.centrifugal_tension_N = F_c;
  check_span_tensions(drive, F_c);

  const std::size_t d = driver_index(g);
  double s_offset = 0.0;
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t i = (d + k) % n, prev = (i + n - 1) % n;
    const Pulley& pulley = g.pulleys[i];
    const double R = pulley.pitch_radius_mm, alpha = g.wrap_rad[i];
    PulleyCycle pc;
    pc.name = pulley.name;
    pc.role = pulley.role;
    pc.wrap_rad = alpha;
    pc.radius_mm = R;
    pc.F_in_N = drive.span_tension_N[prev];
    pc.F_out_N = drive.span_tension_N[i];
    pc.c0 = belt.c_N / (R * R * belt.k1_MPa);
    pc.capstan_limit = capstan_ratio(mu, alpha, belt.wedge_half_angle_rad);
    const double Fe_in = pc.F_in_N - F_c, Fe_out = pc.F_out_N - F_c;
    const bool bend = o.effects.bending_zones && belt.EI_Nmm2 > 0.0;
    const std::string key = "drive.pulleys[" + std::to_string(i) + "]";
    const double contact_free = set_zone_angles(pc, belt, bend, Fe_in, Fe_out, key);

    ArcParameters ap{mu, belt.wedge_half_angle_rad, pc.c0,
                     pulley.role == PulleyRole::idler ? PulleyRole::driven : pulley.role};
    validate(ap);
    const SlidingArc arc = solve_sliding_arc(pc, ap, Fe_out / Fe_in, contact_free, o, key);
    pc.non_sliding_rad = contact_free - pc.sliding_rad;

    const ZoneBounds z = zone_bounds(pc, g.spans[prev].length_mm, g.spans[i].length_mm, s_offset);
    const PulleySampler sampler{drive, o, pc, arc, z, static_cast<int>(i), s_offset, F_c, Fe_in, Fe_out, bend, out};
    sampler.all(k == n);
    out.pulleys.push_back(pc);
    s_offset += z.sL;
  }
  out.cycle_length_mm = s_offset;
  out.cycle_time_s = V > 0.0 ? s_offset / V : 0.0;
  return out;
}

double axial_thrust_N(const LoadCycle& cycle, const BeltSection& belt, int pulley) {
  const double beta = belt.wedge_half_angle_rad;
  auto q = [&](const LoadSample& x) {  // axial force per unit length at a sample
    const double bs = std::atan(std::tan(beta) * std::cos(x.gamma_rad));
    return x.p_MPa * belt.height_mm / std::cos(beta) * (std::cos(beta) + x.friction_used * std::sin(bs));
  };
  double thrust = 0.0;
  const auto& xs = cycle.samples;
  for (std::size_t k = 1; k < xs.size(); ++k)  // trapezoid over the pulley's samples
    if (xs[k].pulley == pulley && xs[k - 1].pulley == pulley)
      thrust += 0.5 * (q(xs[k]) + q(xs[k - 1])) * (xs[k].s_mm - xs[k - 1].s_mm);
  return thrust;
}

}  // namespace fitlib::belt
