#include "fitlib/belt/load_cycle.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include "fitlib/core/error.hpp"
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

LoadCycle compute_load_cycle(const DriveCase& drive, const LoadCycleOptions& o) {
  const DriveGeometry& g = drive.geometry;
  const BeltSection& belt = drive.belt;
  const LoadCycleEffects& fx = o.effects;
  const std::size_t n = g.pulleys.size();
  const double mu = drive.friction, V = drive.belt_speed_mm_s;
  if (drive.span_tension_N.size() != n)
    throw core::UsageError("compute_load_cycle: one span tension per pulley expected");
  if (!(belt.height_mm > 0 && belt.width_mm > 0 && belt.area_mm2 > 0))
    throw InputError("belt height, width and area must be positive", {}, 0, 0, "belt.height_mm");
  if (!(belt.c_N > 0)) throw InputError("longitudinal stiffness c must be positive", {}, 0, 0, "belt.stiffness.c_N");
  if (!(belt.k1_MPa > 0)) throw InputError("radial stiffness k1 must be positive", {}, 0, 0, "belt.stiffness.k1_MPa");
  if (!(belt.EI_Nmm2 >= 0)) throw InputError("bending stiffness EI must be >= 0", {}, 0, 0, "belt.stiffness.EI_Nmm2");
  if (!(V >= 0) || !std::isfinite(V)) throw InputError("belt speed must be >= 0", {}, 0, 0, "drive.pulleys");

  LoadCycle out;
  // Centrifugal tension (4.53): ρ [kg/m³]·A [mm²]·V² [mm²/s²] · 1e-12 → N.
  const double F_c = fx.inertia ? belt.density_kg_m3 * belt.area_mm2 * V * V * 1e-12 : 0.0;
  out.centrifugal_tension_N = F_c;
  for (std::size_t i = 0; i < n; ++i) {
    const double F = drive.span_tension_N[i];
    if (!(F - F_c > 0.0)) {
      const bool lifts = F_c > 0.0 && F > 0.0;
      throw InputError(
          lifts ? "centrifugal tension " + std::to_string(F_c) + " N exceeds the tension " +
                      std::to_string(F) + " N of the span leaving '" + g.pulleys[i].name +
                      "': the belt lifts off"
                : "span leaving '" + g.pulleys[i].name +
                      "' has no tension: the belt does not press on the pulleys",
          {}, 0, 0, lifts ? "drive.pulleys" : "drive.slack_tension_N");
    }
  }

  const std::size_t d = driver_index(g);
  double s_offset = 0.0;
  for (std::size_t k = 1; k <= n; ++k) {
    const std::size_t i = (d + k) % n, prev = (i + n - 1) % n;
    const Pulley& pulley = g.pulleys[i];
    const double R = pulley.pitch_radius_mm, alpha = g.wrap_rad[i];
    const double F_in = drive.span_tension_N[prev], F_out = drive.span_tension_N[i];
    const double Fe_in = F_in - F_c, Fe_out = F_out - F_c;
    PulleyCycle pc;
    pc.name = pulley.name;
    pc.role = pulley.role;
    pc.wrap_rad = alpha;
    pc.radius_mm = R;
    pc.F_in_N = F_in;
    pc.F_out_N = F_out;
    pc.c0 = belt.c_N / (R * R * belt.k1_MPa);
    pc.capstan_limit = capstan_ratio(mu, alpha, belt.wedge_half_angle_rad);

    // Free-span contact angles (4.13) and zone lengths (4.37 with φ_Eref = s0FB − s0FC of the
    // reference case, i.e. Eq 4.12 continued until K0 = 1; decisions.md).
    const bool bend = fx.bending_zones && belt.EI_Nmm2 > 0.0;
    auto root_EI0_over_F0 = [&](double Fe) { return std::sqrt(belt.EI_Nmm2 / Fe) / R; };
    if (bend) {
      pc.phi_C_in_rad = std::atan(root_EI0_over_F0(Fe_in) * ZoneConstants::K0C_in);
      pc.phi_C_out_rad = std::atan(root_EI0_over_F0(Fe_out) * ZoneConstants::K0C_out);
      pc.phi_E_in_rad = root_EI0_over_F0(Fe_in) * std::log(1.0 / ZoneConstants::K0C_in);
      pc.phi_E_out_rad = root_EI0_over_F0(Fe_out) * std::log(1.0 / ZoneConstants::K0C_out);
    }
    const double contact_free =
        alpha - pc.phi_C_in_rad - pc.phi_C_out_rad - pc.phi_E_in_rad - pc.phi_E_out_rad;
    const std::string key = "drive.pulleys[" + std::to_string(i) + "]";
    if (!(contact_free > 0.0))
      throw InputError("wrap angle " + std::to_string(alpha * 180 / kPi) + " deg of pulley '" +
                           pulley.name + "' is smaller than its entrance and exit zones (" +
                           std::to_string((alpha - contact_free) * 180 / kPi) +
                           " deg): the belt does not seat",
                       {}, 0, 0, key);

    // Sliding arc.
    ArcParameters ap{mu, belt.wedge_half_angle_rad, pc.c0,
                     pulley.role == PulleyRole::idler ? PulleyRole::driven : pulley.role};
    validate(ap);
    const double kappa_end = Fe_out / Fe_in;
    const bool slides = pulley.role != PulleyRole::idler && std::abs(kappa_end - 1.0) > 1e-12;
    std::unique_ptr<ClosedFormArc> closed;
    OdeArc ode;
    bool use_ode = false;
    if (slides) {
      if (pulley.role == PulleyRole::driver ? kappa_end > 1.0 : kappa_end < 1.0)
        throw InputError("pulley '" + pulley.name + "' (" + to_string(pulley.role) +
                             ") would need the belt force to " +
                             (kappa_end > 1.0 ? "rise" : "fall") + " over it: check roles and torques",
                         {}, 0, 0, key + ".role");
      pc.gamma_prime_P = sliding_angle_slope_at_P(ap);
      closed = std::make_unique<ClosedFormArc>(ap);
      pc.sliding_closed_form_rad = closed->sliding_arc_length(kappa_end);
      use_ode = fx.full_ode || pc.sliding_closed_form_rad < 0.0;
      if (use_ode) {
        ode = integrate_sliding_arc(ap, kappa_end, contact_free, o.ode_tolerance);
        pc.sliding_ode_rad = ode.reached_kappa_end ? ode.phi_end_rad : -1.0;
        pc.sliding_rad = pc.sliding_ode_rad;
        pc.arc_method = fx.full_ode ? "ode" : "ode (closed form out of range)";
      } else {
        pc.sliding_rad = pc.sliding_closed_form_rad;
        pc.arc_method = "closed-form";
      }
      if (!(pc.sliding_rad >= 0.0) || pc.sliding_rad > contact_free)
        throw InputError(
            "belt slips on pulley '" + pulley.name + "': the tension ratio " +
                std::to_string(std::max(kappa_end, 1.0 / kappa_end)) + " needs a longer sliding arc than the " +
                std::to_string(contact_free * 180 / kPi) + " deg of contact available (capstan limit exp(mu alpha/sin beta) = " +
                std::to_string(pc.capstan_limit) + "); lower the torque or raise the tension",
            {}, 0, 0, "drive.torque_Nm");
    } else {
      pc.arc_method = "none";
    }
    pc.non_sliding_rad = contact_free - pc.sliding_rad;

    // Zone boundaries (4.15–4.17) with a = tangent span lengths.
    const double a_in = g.spans[prev].length_mm, a_out = g.spans[i].length_mm;
    pc.s_start_mm = s_offset;
    const double sL = 0.5 * (a_in + a_out) + alpha * R;
    const double s_Cin = 0.5 * a_in + pc.phi_C_in_rad * R;
    const double s_Ein = s_Cin + pc.phi_E_in_rad * R;
    const double s_Cout = sL - 0.5 * a_out - pc.phi_C_out_rad * R;
    const double s_Eout = s_Cout - pc.phi_E_out_rad * R;
    const double s_NS = s_Eout - pc.sliding_rad * R;
    pc.s_Cin_mm = s_offset + s_Cin;
    pc.s_Ein_mm = s_offset + s_Ein;
    pc.s_NS_mm = s_offset + s_NS;
    pc.s_Eout_mm = s_offset + s_Eout;
    pc.s_Cout_mm = s_offset + s_Cout;
    pc.s_end_mm = s_offset + sL;

    const double F0P = Fe_in / (R * R * belt.k1_MPa);
    const double fP = sinking_ratio_at_P(ap);
    const double p_in = side_pressure_MPa(Fe_in, R, belt, mu, kPi);
    auto arc_at = [&](double phi) {
      return use_ode ? interpolate(ode, phi) : closed ? closed->at(phi) : ArcPoint{phi, 1.0, kPi, fP};
    };
    const ArcPoint arc_end = arc_at(pc.sliding_rad);
    const double p_Eout = side_pressure_MPa(arc_end.kappa * Fe_in, R, belt, mu, arc_end.gamma_rad);

    auto push = [&](double s_local, Zone z, double F, double K, double p, double gamma,
                    double slide, double friction_used) {
      LoadSample x;
      x.s_mm = s_offset + s_local;
      x.t_s = V > 0.0 ? x.s_mm / V : 0.0;
      x.pulley = static_cast<int>(i);
      x.zone = z;
      x.F_N = F;
      x.K_1_mm = K;
      x.p_MPa = std::max(p, 0.0);
      x.gamma_rad = gamma;
      x.slide_mm_s = slide;
      x.friction_used = friction_used;
      out.samples.push_back(x);
    };
    const double lambda_in = bend ? std::sqrt(Fe_in / belt.EI_Nmm2) : INFINITY;
    const double lambda_out = bend ? std::sqrt(Fe_out / belt.EI_Nmm2) : INFINITY;
    const double K0C_in = bend ? ZoneConstants::K0C_in : 1.0, K0C_out = bend ? ZoneConstants::K0C_out : 1.0;

    // 1 free span, entrance side.
    sample_zone(0.0, s_Cin, o, false, [&](double s) {
      push(s, Zone::free_span_in, F_in, free_span_curvature(K0C_in / R, lambda_in, s, s_Cin), 0, 0, 0, 0);
    });
    // 2 entrance zone: γ = 180°, θ_E = −0.000418, x0C = 0 (A5 = 0, 4.40), p ∝ x0 (4.48).
    if (bend) {
      const double phiE = pc.phi_E_in_rad, one_m = 1.0 - kEntrance.K0C;
      const double A4 = -ZoneConstants::theta_E_in / (phiE * one_m) - kEntrance.P(1.0);
      auto x0 = [&](double psi) { return phiE * phiE * one_m * (kEntrance.X(psi) + A4 * psi); };
      const double x0E = x0(1.0);
      sample_zone(s_Cin, s_Ein, o, false, [&](double s) {
        const double psi = (s - s_Cin) / (s_Ein - s_Cin);
        const double theta = -phiE * one_m * (kEntrance.P(psi) + A4);
        push(s, Zone::entrance, F_in, kEntrance.K0(psi) / R, p_in * x0(psi) / x0E, kPi,
             V * std::abs(theta), mu);
      });
    }
    // 3 non-sliding arc.
    sample_zone(s_Ein, s_NS, o, false, [&](double s) {
      push(s, Zone::non_sliding, F_in, 1.0 / R, p_in, kPi, 0.0, mu);
    });
    // 4 sliding arc (4.18): φ = (s − s_NS)/R.
    sample_zone(s_NS, s_Eout, o, false, [&](double s) {
      const ArcPoint a = arc_at((s - s_NS) / R);
      const double Fe = a.kappa * Fe_in;
      // Circumferential slip (A.20): (x0 − x0P) + (ε − εP); v_s sin γ equals it (A.5).
      const double circ = F0P * ((a.x0_over_F0P - fP) + (a.kappa - 1.0) / pc.c0);
      const double sg = std::sin(a.gamma_rad);
      push(s, Zone::sliding, Fe + F_c, 1.0 / R, side_pressure_MPa(Fe, R, belt, mu, a.gamma_rad),
           a.gamma_rad, std::abs(sg) > 1e-12 ? V * std::abs(circ / sg) : 0.0, mu);
    });
    // 5 exit zone: θ_Eout from the exit sliding angle (4.47) with γ_NC = 1° (driven), 359° (driver).
    if (bend) {
      const double phiE = pc.phi_E_out_rad, one_m = 1.0 - kExit.K0C;
      const double gamma_NE = arc_end.gamma_rad;
      const double gamma_NC = (pulley.role == PulleyRole::driver ? 359.0 : 1.0) * kPi / 180.0;
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
      sample_zone(s_Eout, s_Cout, o, false, [&](double s) {
        const double psi = (s_Cout - s) / (s_Cout - s_Eout);
        const double theta = theta_E + phiE * one_m * (kExit.P(psi) - kExit.P(1.0));
        double gamma_N = std::atan2(sgn * theta_E * std::sin(gamma_NE), sgn * theta * std::cos(gamma_NE));
        if (gamma_N < 0.0) gamma_N += 2.0 * kPi;
        double used = mu;
        if (fx.driver_exit_ramp && pulley.role == PulleyRole::driver && 1.0 - psi < ramp)
          used = mu * 0.5 * (1.0 + std::cos(2.0 * kPi * (1.0 - psi) / ramp));  // full → 0 → full
        push(s, Zone::exit, F_out, kExit.K0(psi) / R, p_Eout * shape(thetaE_p, psi) / x0E, gamma_N,
             V * std::hypot(circ, theta), used);
      });
    }
    // 6 free span, exit side.
    sample_zone(s_Cout, sL, o, k == n, [&](double s) {
      push(s, Zone::free_span_out, F_out,
           free_span_curvature(K0C_out / R, lambda_out, sL - s, sL - s_Cout), 0, 0, 0, 0);
    });
    out.pulleys.push_back(pc);
    s_offset += sL;
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
