#include "fitlib/belt/contact_arc.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <boost/numeric/odeint.hpp>

#include "fitlib/core/enum_names.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {
namespace {
using core::kPi;

// β_s = arctan(tan β cos γ) (A.10)
double skew_wedge(double beta, double gamma) { return std::atan(std::tan(beta) * std::cos(gamma)); }

// Bisection for a sign change of g on [lo, hi]; g(lo) and g(hi) must differ in sign.
template <typename G>
double bisect(G g, double lo, double hi) {
  double g_lo = g(lo);
  for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    const double g_mid = g(mid);
    if ((g_mid < 0) == (g_lo < 0)) {
      lo = mid;
      g_lo = g_mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}
}  // namespace

constexpr core::EnumName<PulleyRole> kPulleyRoleNames[] = {
    {PulleyRole::driver, "driver"}, {PulleyRole::driven, "driven"}, {PulleyRole::idler, "idler"}};

const char* to_string(PulleyRole role) { return core::enum_name(kPulleyRoleNames, role); }

void validate(const ArcParameters& a) {
  if (!(a.friction >= 0.0) || !std::isfinite(a.friction))
    throw core::InputError("friction coefficient must be finite and >= 0", {}, 0, 0,
                           "conditions.friction");
  if (!(a.wedge_half_angle_rad > 0.0 && a.wedge_half_angle_rad < kPi / 2))
    throw core::InputError("wedge half-angle must lie in (0, 90) degrees", {}, 0, 0,
                           "belt.wedge_half_angle_deg");
  if (!(a.c0 > 0.0) || !std::isfinite(a.c0))
    throw core::InputError("belt stiffness ratio c0 = c/(R^2 k1) must be positive", {}, 0, 0,
                           "belt.stiffness");
  if (a.wedge_half_angle_rad + std::atan(a.friction) >= kPi / 2)
    throw core::InputError(
        "self-locking groove: mu >= cot(beta) (mu = " + core::format_number(a.friction) +
            "), the belt wedges and the V-belt theory (A.23) does not apply",
        {}, 0, 0, "conditions.friction");
}

double sinking_ratio_at_P(const ArcParameters& a) {
  return 1.0 / std::tan(a.wedge_half_angle_rad + std::atan(a.friction));
}

double sinking_function(const ArcParameters& a, double gamma) {
  const double beta = a.wedge_half_angle_rad, mu = a.friction;
  const double bs = skew_wedge(beta, gamma);
  return (std::cos(beta) + mu * std::sin(bs)) / (std::sin(beta) - mu * std::cos(bs) * std::cos(gamma));
}

double sinking_function_derivative(const ArcParameters& a, double gamma) {
  // f as a function of u = cos γ, then chain rule du/dγ = −sin γ.
  const double beta = a.wedge_half_angle_rad, mu = a.friction, tb = std::tan(beta);
  const double u = std::cos(gamma);
  const double bs = std::atan(tb * u);
  const double bs_u = tb / (1.0 + tb * tb * u * u);
  const double N = std::cos(beta) + mu * std::sin(bs);
  const double D = std::sin(beta) - mu * u * std::cos(bs);
  const double N_u = mu * std::cos(bs) * bs_u;
  const double D_u = -mu * (std::cos(bs) - u * std::sin(bs) * bs_u);
  return (N_u * D - N * D_u) / (D * D) * (-std::sin(gamma));
}

double force_log_slope(const ArcParameters& a, double gamma) {
  const double beta = a.wedge_half_angle_rad, mu = a.friction;
  const double bs = skew_wedge(beta, gamma);
  return mu * std::cos(bs) * std::sin(gamma) / (std::sin(beta) - mu * std::cos(bs) * std::cos(gamma));
}

double sliding_angle_slope_at_P(const ArcParameters& a) {
  const double T = std::tan(a.wedge_half_angle_rad) + a.friction;
  const double fP = sinking_ratio_at_P(a);
  const double b = 0.5 - T * fP;
  const double c = -T * (1.0 + a.c0 * fP) / (2.0 * a.c0);
  const double disc = std::sqrt(b * b - 4.0 * c);  // c < 0: two real roots of opposite sign
  // Stable root formulas: q = −(b + sign(b)√disc)/2; roots q and c/q.
  const double q = -0.5 * (b + (b >= 0 ? disc : -disc));
  const double r1 = q, r2 = c / q;
  return a.role == PulleyRole::driver ? std::max(r1, r2) : std::min(r1, r2);
}

double asymptotic_sliding_angle(const ArcParameters& a) {
  const double beta = a.wedge_half_angle_rad, mu = a.friction;
  auto g = [&](double ga) {
    const double bs = skew_wedge(beta, ga);
    const double den = std::sin(beta) - mu * std::cos(bs) * std::cos(ga);
    const double mu_fa = mu * std::cos(bs) * std::sin(ga) / den;
    return 1.0 / a.c0 + sinking_function(a, ga) * (1.0 + mu_fa * std::tan(ga));
  };
  // g(π) = 1/c0 + fP > 0; g → −∞ as γ → π/2⁺ (μ > 0).
  return bisect(g, kPi / 2 + 1e-12, kPi);
}

double capstan_ratio(double friction, double wrap_rad, double wedge_half_angle_rad) {
  return std::exp(friction * wrap_rad / std::sin(wedge_half_angle_rad));
}

ClosedFormArc::ClosedFormArc(const ArcParameters& a) : a_(a) {
  validate(a);
  if (a.role == PulleyRole::idler)
    throw core::UsageError("an idler pulley has no sliding arc");
  gamma_prime_P_ = sliding_angle_slope_at_P(a);
  const double mu = a.friction, beta = a.wedge_half_angle_rad;
  if (a.role == PulleyRole::driven) {
    if (mu > 0.0) {
      gamma_a_ = asymptotic_sliding_angle(a);
      const double bs = skew_wedge(beta, gamma_a_);
      mu_fa_ = mu * std::cos(bs) * std::sin(gamma_a_) /
               (std::sin(beta) - mu * std::cos(bs) * std::cos(gamma_a_));  // (A.28)
    } else {
      gamma_a_ = kPi;
    }
    mu_fP_ = -gamma_prime_P_ * mu / (std::tan(beta) + mu);  // (A.26)
  } else {
    mu_e_ = mu / std::sin(beta);  // (A.33)
  }
}

ArcPoint ClosedFormArc::at(double phi) const {
  ArcPoint pt;
  pt.phi_rad = phi;
  const double gp = gamma_prime_P_;
  if (a_.friction == 0.0) {
    pt.kappa = 1.0;
    pt.gamma_rad = kPi;
  } else if (a_.role == PulleyRole::driven) {
    // (A.25) in logarithms: ln κ = (μfa²/μ'fP) ln cosh(μ'fP φ/μfa); ln cosh stable for large y.
    const double y = mu_fP_ / mu_fa_ * phi;
    const double ay = std::abs(y);
    const double log_cosh = ay + std::log1p(std::exp(-2.0 * ay)) - std::log(2.0);
    pt.kappa = std::exp(mu_fa_ * mu_fa_ / mu_fP_ * log_cosh);
    pt.gamma_rad = kPi + (kPi - gamma_a_) * std::tanh(gp * phi / (kPi - gamma_a_));  // (A.31)
  } else {
    const double arg = std::max((1.0 + mu_e_ * std::cos(std::min(gp * phi, kPi))) / (1.0 + mu_e_), 0.0);
    pt.kappa = std::pow(arg, 1.0 / gp);                                           // (A.32)
    pt.gamma_rad = std::min(kPi + gp * phi, kDriverSlidingAngleLimit_rad);        // (A.34–35)
  }
  pt.x0_over_F0P = pt.kappa * sinking_function(a_, pt.gamma_rad);
  return pt;
}

double ClosedFormArc::sliding_arc_length(double kappa_end) const {
  if (kappa_end == 1.0) return 0.0;
  if (a_.friction == 0.0) return -1.0;
  if (a_.role == PulleyRole::driven) {
    if (kappa_end < 1.0) return -1.0;
    // cosh(y) = κ^(μ'fP/μfa²), y = μ'fP φ/μfa
    const double log_cosh = std::log(kappa_end) * mu_fP_ / (mu_fa_ * mu_fa_);
    // acosh(e^L) = L + ln(1 + sqrt(1 − e^{−2L}))
    const double y = log_cosh + std::log1p(std::sqrt(-std::expm1(-2.0 * log_cosh)));
    return y * mu_fa_ / mu_fP_;
  }
  if (kappa_end > 1.0) return -1.0;
  const double gp = gamma_prime_P_;
  const double cos_arg = ((1.0 + mu_e_) * std::pow(kappa_end, gp) - 1.0) / mu_e_;
  if (cos_arg < -1.0) return -1.0;  // needs γ'_P φ > π: outside the closed form
  return std::acos(cos_arg) / gp;
}

namespace {
namespace odeint = boost::numeric::odeint;
using ArcState = std::array<double, 2>;  // κ, γ
using ArcStepper = odeint::dense_output_runge_kutta<
    odeint::controlled_runge_kutta<odeint::runge_kutta_dopri5<ArcState>>>;

void record(OdeArc& arc, const ArcParameters& a, double phi, const ArcState& y) {
  arc.points.push_back({phi, y[0], y[1], y[0] * sinking_function(a, y[1])});
}

// The sliding arc's equations in κ and γ: κ' from (A.21), γ' from (A.22); `held` freezes the
// driver's γ at γ_Lim.
struct SlidingArcRhs {
  const ArcParameters& a;
  double fP;
  bool held = false;
  void operator()(const ArcState& y, ArcState& dy, double) const {
    const double kappa = y[0], gamma = held ? kDriverSlidingAngleLimit_rad : y[1];
    const double dk = kappa * force_log_slope(a, gamma);
    dy[0] = dk;
    if (held) {
      dy[1] = 0.0;
      return;
    }
    const double f = sinking_function(a, gamma);
    // ξ = x0/F0P = κ f; (A.22) ξ' tan γ = −[(ξ − fP) + (κ − 1)/c0]
    const double xi_prime = -((kappa * f - fP) + (kappa - 1.0) / a.c0) / std::tan(gamma);
    dy[1] = (xi_prime - dk * f) / (kappa * sinking_function_derivative(a, gamma));
  }
};

// Bisection on the dense output for the first φ in (lo, hi] where κ has passed kappa_end.
template <typename Passed>
double passing_phi(const ArcStepper& stepper, Passed passed, double lo, double hi) {
  ArcState s;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    stepper.calc_state(mid, s);
    (passed(s) ? hi : lo) = mid;
  }
  return hi;
}

// Steps the arc from the stepper's state to κ = kappa_end (ends the arc there) or to phi_max.
template <typename Passed>
void march_arc(const ArcParameters& a, ArcStepper& stepper, SlidingArcRhs& rhs, Passed passed,
               double phi_max, OdeArc& arc) {
  const bool driver = a.role == PulleyRole::driver;
  while (stepper.current_time() < phi_max) {
    stepper.do_step(rhs);
    ArcState cur = stepper.current_state();
    const double t1 = stepper.current_time();
    if (!std::isfinite(cur[0]) || !std::isfinite(cur[1]))
      throw core::NumericalError("sliding-arc ODE diverged at phi = " + core::format_number(t1));
    const double t_hit = std::min(t1, phi_max);
    ArcState at_hit = cur;
    if (t_hit < t1) stepper.calc_state(t_hit, at_hit);
    if (passed(at_hit)) {
      const double hi = passing_phi(stepper, passed, stepper.previous_time(), t_hit);
      ArcState s;
      stepper.calc_state(hi, s);
      if (rhs.held) s[1] = kDriverSlidingAngleLimit_rad;
      record(arc, a, hi, s);
      arc.reached_kappa_end = true;
      arc.phi_end_rad = hi;
      return;
    }
    if (driver && !rhs.held && cur[1] >= kDriverSlidingAngleLimit_rad) {
      rhs.held = true;
      cur[1] = kDriverSlidingAngleLimit_rad;
      stepper.initialize(cur, t1, 1e-3);
    }
    if (t_hit < t1) {
      record(arc, a, t_hit, at_hit);
      break;
    }
    record(arc, a, t1, cur);
  }
  arc.phi_end_rad = phi_max;
}

}  // namespace

OdeArc integrate_sliding_arc(const ArcParameters& a, double kappa_end, double phi_max,
                             double tolerance) {
  validate(a);
  OdeArc arc;
  const ArcState start{1.0, kPi};
  record(arc, a, 0.0, start);
  if (kappa_end == 1.0 || a.friction == 0.0) {
    arc.reached_kappa_end = kappa_end == 1.0;
    arc.phi_end_rad = arc.reached_kappa_end ? 0.0 : phi_max;
    if (!arc.reached_kappa_end) record(arc, a, phi_max, start);
    return arc;
  }
  // Series start (A.24): γ = π + γ'_P φ, κ = 1 − μ γ'_P φ²/(2(tan β + μ)).
  const double gp = sliding_angle_slope_at_P(a);
  const double T = std::tan(a.wedge_half_angle_rad) + a.friction;
  const double phi0 = std::min(1e-4, 1e-3 / std::abs(gp));
  const ArcState y{1.0 - a.friction * gp * phi0 * phi0 / (2.0 * T), kPi + gp * phi0};
  ArcStepper stepper = odeint::make_dense_output(tolerance, tolerance, 0.02,
                                                 odeint::runge_kutta_dopri5<ArcState>());
  stepper.initialize(y, phi0, std::min(phi0, 1e-3));
  record(arc, a, phi0, y);
  const bool increasing = kappa_end > 1.0;
  auto passed = [&](const ArcState& s) {
    return increasing ? s[0] >= kappa_end : s[0] <= kappa_end;
  };
  if (passed(y)) {
    arc.reached_kappa_end = true;
    arc.phi_end_rad = phi0;
    return arc;
  }
  SlidingArcRhs rhs{a, sinking_ratio_at_P(a)};
  march_arc(a, stepper, rhs, passed, phi_max, arc);
  return arc;
}

ArcPoint interpolate(const OdeArc& arc, double phi) {
  const auto& p = arc.points;
  if (phi <= p.front().phi_rad) return p.front();
  if (phi >= p.back().phi_rad) return p.back();
  const auto it = std::upper_bound(p.begin(), p.end(), phi,
                                   [](double v, const ArcPoint& q) { return v < q.phi_rad; });
  const ArcPoint& b = *it;
  const ArcPoint& a = *(it - 1);
  const double w = (phi - a.phi_rad) / (b.phi_rad - a.phi_rad);
  auto lerp = [w](double u, double v) { return u + w * (v - u); };
  return {phi, lerp(a.kappa, b.kappa), lerp(a.gamma_rad, b.gamma_rad),
          lerp(a.x0_over_F0P, b.x0_over_F0P)};
}

}  // namespace fitlib::belt
