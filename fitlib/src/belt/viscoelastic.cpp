#include "fitlib/belt/viscoelastic.hpp"

#include <cmath>
#include <string>

#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {
namespace {
using core::InputError;
using core::kPi;
}  // namespace

double tension_test_b_mm(double d0, double r, double f) {
  return d0 + 2.0 * r * (f > 0 ? -std::expm1(-f * kPi / 2) / f : kPi / 2);
}

double tension_test_loading_N(const ThreeParameterBelt& m, double v, double b, double t, double theta,
                              double f) {
  return m.S_N * v * (t + (m.tau_eps_s - m.tau_T_s) * (-std::expm1(-t / m.tau_T_s))) *
         std::exp(-f * theta) / b;
}

double tension_test_loading_as_printed_N(const ThreeParameterBelt& m, double v, double b, double t,
                                         double theta, double f) {
  return m.S_N * v * (t + (m.tau_eps_s - m.tau_T_s) * (-std::expm1(-t / m.tau_eps_s))) *
         std::exp(-f * theta) / b;
}

double relaxation_N(const ThreeParameterBelt& m, double T_x, double T_inf, double t) {
  return T_inf + (T_x - T_inf) * std::exp(-t / m.tau_T_s);
}

std::vector<double> integrate_three_parameter(const ThreeParameterBelt& m, const std::vector<double>& t,
                                              const std::vector<double>& eps, double T0) {
  // T + τ_T Ṫ = S(ε + τ_ε ε̇); over a step with ε linear (slope k): exact update
  // T(t+h) = e^{−h/τ_T} T + S ∫ e^{−(h−u)/τ_T}(ε(u) + τ_ε k) du / τ_T.
  std::vector<double> T(t.size(), T0);
  const double tT = m.tau_T_s;
  for (std::size_t n = 1; n < t.size(); ++n) {
    const double h = t[n] - t[n - 1], k = (eps[n] - eps[n - 1]) / h, e0 = eps[n - 1];
    const double a = std::exp(-h / tT);
    // ∫0^h e^{−(h−u)/τ}(e0 + k u) du/τ = e0(1 − a) + k[h − τ(1 − a)]
    const double forced = e0 * (1 - a) + k * (h - tT * (1 - a)) + m.tau_eps_s * k * (1 - a);
    T[n] = a * T[n - 1] + m.S_N * forced;
  }
  return T;
}

namespace {
// One pulley of the steady drive, entered with tension T_in and elongation eps_in; leaves with
// T_out. direction = −1 on the driver (tension falls), +1 on the driven pulley.
ViscoelasticPulley march_pulley(const ViscoelasticDriveInput& in, double T_in, double eps_in,
                                double T_out, double direction) {
  const double S = in.belt.S_N, f = in.friction, w = in.omega_rad_s;
  const double aT = w * in.belt.tau_T_s, ae = w * in.belt.tau_eps_s;  // ωτ_T, ωτ_ε
  const double h = 1.0 / in.steps_per_rad;
  ViscoelasticPulley p;
  auto record = [&](double th, double T, double e) {
    p.theta_rad.push_back(th);
    p.T_N.push_back(T);
    p.eps.push_back(e);
  };
  // ε along a sliding arc with T = T0 e^{sfθ}: ae ε' + ε = T(1 + s f aT)/S, exact for each step
  // (the forcing is exponential in θ): particular ε_p = c e^{sfθ}, c = T0(1 + s f aT)/(S(1 + s f ae)).
  auto slide_eps = [&](double T0, double e0, double s, double th) {
    if (ae == 0.0) return T0 * std::exp(s * f * th) * (1 + s * f * aT) / S;
    const double c = T0 * (1 + s * f * aT) / (S * (1 + s * f * ae));
    return c * std::exp(s * f * th) + (e0 - c) * std::exp(-th / ae);
  };
  auto adhesion_ok = [&](double T, double e) { return std::abs(S * e - T) <= f * aT * T * (1 + 1e-12); };
  // Entrance sliding arc: the belt slides while adhesion would need |T'| > fT.
  double th = 0.0, T = T_in, e = eps_in;
  record(th, T, e);
  const double s_in = S * eps_in > T_in ? 1.0 : -1.0;
  if (aT > 0.0 && !adhesion_ok(T, e)) {
    const double T0 = T_in, e0 = eps_in;
    while (!adhesion_ok(T, e)) {
      th += h;
      if (th > kPi) throw InputError("entrance sliding spans the whole wrap", {}, 0, 0, "viscoelastic");
      T = T0 * std::exp(s_in * f * th);
      e = slide_eps(T0, e0, s_in, th);
      record(th, T, e);
    }
  } else if (aT == 0.0) {
    T = S * e;  // τ_T = 0: T follows ε at once
  }
  p.entrance_sliding_rad = th;
  p.adhesion_elongation = e;
  // Adhesion arc θ_a, then main sliding to T_out: θ_a + ln(T_out/T_3)/(direction f) = wrap − θ_e.
  const double rest = kPi - th, T2 = T, ea = e;
  auto T3 = [&](double ta) { return aT > 0 ? S * ea + (T2 - S * ea) * std::exp(-ta / aT) : S * ea; };
  auto g = [&](double ta) { return ta + std::log(T_out / T3(ta)) / (direction * f) - rest; };
  if (!(g(rest) >= 0.0))
    throw InputError("the belt slips: the tension ratio needs more than the wrap", {}, 0, 0,
                     "viscoelastic.tight_N");
  double lo = 0.0, hi = rest;
  if (g(lo) >= 0.0) hi = lo;  // no adhesion arc left: the sliding arc takes the whole rest
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) >= 0.0 ? hi : lo) = mid;
  }
  p.adhesion_rad = hi;
  for (double ta = h; ta < hi; ta += h) record(th + ta, T3(ta), ea);
  th += hi;
  const double T3v = T3(hi);
  p.main_sliding_rad = kPi - th;
  record(th, T3v, ea);
  for (double ts = h; ts <= p.main_sliding_rad + 1e-12; ts += h) {
    const double ts_c = std::min(ts, p.main_sliding_rad);
    const double e_s = slide_eps(T3v, ea, direction, ts_c);
    record(th + ts_c, T3v * std::exp(direction * f * ts_c), e_s);
    p.max_relative_slip = std::max(p.max_relative_slip, std::abs(e_s - ea));
  }
  return p;
}
}  // namespace

ViscoelasticDrive solve_viscoelastic_drive(const ViscoelasticDriveInput& in) {
  if (!(in.tight_N > in.slack_N && in.slack_N > 0))
    throw InputError("need tight > slack > 0", {}, 0, 0, "viscoelastic.tight_N");
  if (!(in.belt.S_N > 0 && in.belt.tau_T_s >= 0 && in.belt.tau_eps_s >= 0 && in.friction > 0 &&
        in.omega_rad_s > 0 && in.radius_mm > 0))
    throw InputError("S, friction, omega, radius must be positive and the times >= 0", {}, 0, 0,
                     "viscoelastic");
  const double span = in.center_distance_mm;  // free length of each span on equal pulleys
  const double decay = in.belt.tau_eps_s > 0
                           ? std::exp(-(span / in.radius_mm) / (in.omega_rad_s * in.belt.tau_eps_s))
                           : 0.0;  // s/(vτ_ε) with v = ωr
  auto free_span = [&](double e0, double T) { return T / in.belt.S_N + (e0 - T / in.belt.S_N) * decay; };
  // Fixed point on the elongation entering the driver (the tight span's ε).
  ViscoelasticDrive d;
  double eps = in.tight_N / in.belt.S_N;
  for (d.iterations = 1; d.iterations <= 500; ++d.iterations) {
    d.driver = march_pulley(in, in.tight_N, eps, in.slack_N, -1.0);
    const double e_slack = free_span(d.driver.eps.back(), in.slack_N);
    d.driven = march_pulley(in, in.slack_N, e_slack, in.tight_N, +1.0);
    const double next = free_span(d.driven.eps.back(), in.tight_N);
    if (std::abs(next - eps) <= 1e-13 * std::max(1.0, std::abs(eps) * 1e3)) {
      eps = next;
      return d;
    }
    eps = next;
  }
  throw core::NumericalError("viscoelastic drive: elongation loop did not close in 500 passes");
}

}  // namespace fitlib::belt
