#include "fitlib/belt/viscoelastic.hpp"

#include <array>
#include <functional>
#include <cmath>

#include <ceres/ceres.h>
#include <string>
#include <vector>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/time_series.hpp"
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
  // The model's three-parameter solid (exact for ε linear over each step, from rest with a jump
  // to ε(t0)), plus the free decay (T0 − T(t0)) e^{−(t−t0)/τ_T} that starts it at T0.
  if (!(m.tau_T_s > 0.0))
    throw core::UsageError("three-parameter belt: the time integration needs tau_T > 0");
  const auto series = model::three_parameter_solid(m.S_N, m.tau_T_s, m.tau_eps_s);
  std::vector<double> T = series.stress({t, eps});
  if (T.empty()) return T;
  const double offset = T0 - T[0];
  for (std::size_t n = 0; n < T.size(); ++n) T[n] += offset * std::exp(-(t[n] - t[0]) / m.tau_T_s);
  return T;
}

namespace {
// τ ε̇ + ε = g(t) over a step h with g linear from g0 with slope k (exact).
double relax_step(double eps0, double g0, double k, double h, double tau) {
  if (tau <= 0.0) return g0 + k * h;
  const double a = std::exp(-h / tau);
  return a * eps0 + g0 * (1 - a) + k * (h - tau * (1 - a));
}
}  // namespace

namespace {

// The tension test's state: strain and tension of every wrapped element θ_i and of the free
// span, advanced step by step under the imposed elongation (Sorge & Cammalleri, Eqs 1 and 6).
class TensionTest {
 public:
  explicit TensionTest(const TensionTestInput& in)
      : in_(in), m_(in.belt), M_(in.nodes), theta_(M_), weight_(M_), eps_(M_, 0.0), T_(M_, 0.0) {
    for (int i = 0; i < M_; ++i) {  // Simpson-free trapezoid on a fine grid: ∫0^{π/2} ε dθ
      theta_[i] = 0.5 * kPi * i / (M_ - 1);
      weight_[i] = 0.5 * kPi / (M_ - 1) * ((i == 0 || i == M_ - 1) ? 0.5 : 1.0);
    }
  }

  // Loading: all elements slide outward.
  void load(TensionTestResult& out) {
    const double h = in_.load_time_s / in_.steps_per_phase;
    const std::vector<int> outward(M_, -1);
    const std::vector<double> none(M_, 0.0);
    out.loading.push_back({0.0, 0.0, 0.0, 0.5 * kPi});
    for (int n = 1; n <= in_.steps_per_phase; ++n) {
      double tb = 0.0;
      solve_step(in_.v_mm_s * n * h, h, [&](double) { return outward; }, [&](double) { return none; }, tb);
      out.loading.push_back({n * h, in_.v_mm_s * n * h, T_fs_, 0.5 * kPi});
    }
  }

  // Unloading: frozen elongation and relaxing tension in the adhesion arc (closed form of (1)).
  void unload(TensionTestResult& out) {
    const std::vector<double> eps_x = eps_, T_x = T_;
    std::vector<bool> sliding(M_, false);
    const double h = in_.load_time_s / in_.steps_per_phase;
    out.unloading.push_back({0.0, in_.v_mm_s * in_.load_time_s, T_fs_, 0.0});
    for (int n = 1; n <= in_.steps_per_phase; ++n) {
      const double t = n * h;
      std::vector<double> T_adh(M_);
      for (int i = 0; i < M_; ++i)
        T_adh[i] = m_.S_N * eps_x[i] + (T_x[i] - m_.S_N * eps_x[i]) * (m_.tau_T_s > 0 ? std::exp(-t / m_.tau_T_s) : 0.0);
      // Element i slides once T_fs e^{fθ_i} ≤ its adhesion tension (θ ≤ θ_b, Eq 6); it stays sliding.
      auto signs = [&](double T1) {
        std::vector<int> s(M_, 0);
        for (int i = 0; i < M_; ++i) s[i] = (sliding[i] || T1 * std::exp(in_.f * theta_[i]) <= T_adh[i]) ? 1 : 0;
        return s;
      };
      double tb = 0.0;
      solve_step(in_.v_mm_s * (in_.load_time_s - t), h, signs, [&](double) { return T_adh; }, tb);
      for (int i = 0; i < M_; ++i) sliding[i] = sliding[i] || theta_[i] <= tb;
      out.unloading.push_back({t, in_.v_mm_s * (in_.load_time_s - t), T_fs_, tb});
      if (T_fs_ <= 0.0) break;  // a belt carries no compression
    }
  }

 private:
  // One step to span tension T1 under a sliding sign per element (−1 outward, +1 inward, 0
  // adhering); returns the elongation d − d0 it implies and writes the new state to the outs.
  double advance(double T1, double h, const std::vector<int>& sign, const std::vector<double>& T_adh1,
                 std::vector<double>& eps1, std::vector<double>& Tn, double& eps_fs1) const {
    const double k_fs = (T1 - T_fs_) / h;
    eps_fs1 = relax_step(eps_fs_, (T_fs_ + m_.tau_T_s * k_fs) / m_.S_N, k_fs / m_.S_N, h, m_.tau_eps_s);
    double integral = 0.0;
    for (int i = 0; i < M_; ++i) {
      if (sign[i] == 0) {
        eps1[i] = eps_[i];
        Tn[i] = T_adh1[i];
      } else {
        Tn[i] = T1 * std::exp(sign[i] * in_.f * theta_[i]);
        const double k = (Tn[i] - T_[i]) / h;
        eps1[i] = relax_step(eps_[i], (T_[i] + m_.tau_T_s * k) / m_.S_N, k / m_.S_N, h, m_.tau_eps_s);
      }
      integral += weight_[i] * eps1[i];
    }
    return in_.d0_mm * eps_fs1 + 2.0 * in_.r_mm * integral;
  }

  // Bisection on the span tension for the imposed elongation (monotone in T1); moves the state
  // and writes the end of the sliding arc θ_b to t_b.
  void solve_step(double target, double h, const std::function<std::vector<int>(double)>& signs,
                  const std::function<std::vector<double>(double)>& adhesion, double& t_b) {
    std::vector<double> eps1(M_), Tn(M_);
    double e_fs1 = 0.0;
    double lo = T_fs_ - 1e3 - std::abs(T_fs_), hi = T_fs_ + 1e3 + std::abs(T_fs_);
    auto residual = [&](double T1) { return advance(T1, h, signs(T1), adhesion(T1), eps1, Tn, e_fs1) - target; };
    while (residual(lo) > 0) lo -= 2 * (hi - lo);
    while (residual(hi) < 0) hi += 2 * (hi - lo);
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (lo + hi);
      (residual(mid) > 0 ? hi : lo) = mid;
    }
    const double T1 = 0.5 * (lo + hi);
    const auto sg = signs(T1);
    advance(T1, h, sg, adhesion(T1), eps1, Tn, e_fs1);
    eps_ = eps1;
    T_ = Tn;
    eps_fs_ = e_fs1;
    T_fs_ = T1;
    int last = -1;
    for (int i = 0; i < M_; ++i)
      if (sg[i] != 0) last = i;
    t_b = last < 0 ? 0.0 : theta_[last];
  }

  const TensionTestInput& in_;
  const ThreeParameterBelt& m_;
  int M_;
  std::vector<double> theta_, weight_, eps_, T_;
  double eps_fs_ = 0.0, T_fs_ = 0.0;
};

}  // namespace

TensionTestResult simulate_tension_test(const TensionTestInput& in) {
  const ThreeParameterBelt& m = in.belt;
  if (!(in.d0_mm > 0 && in.r_mm > 0 && in.f >= 0 && in.v_mm_s > 0 && in.load_time_s > 0 && in.nodes >= 2 &&
        in.steps_per_phase >= 1 && m.S_N > 0 && m.tau_T_s >= 0 && m.tau_eps_s >= 0))
    throw InputError("tension test: positive geometry, rate, times and sizes needed", {}, 0, 0, "tension_test");
  TensionTestResult out;
  TensionTest test(in);
  test.load(out);
  test.unload(out);
  return out;
}

namespace {
// One pulley's march in θ: the belt's constants at the pulley and the path recorded so far.
struct PulleyMarch {
  double S, f, aT, ae, h;  // S_N, friction, ωτ_T, ωτ_ε, step (rad)
  ViscoelasticPulley p;

  void record(double th, double T, double e) {
    p.theta_rad.push_back(th);
    p.T_N.push_back(T);
    p.eps.push_back(e);
  }
  // ε along a sliding arc with T = T0 e^{sfθ}: ae ε' + ε = T(1 + s f aT)/S, exact for each step
  // (the forcing is exponential in θ): particular ε_p = c e^{sfθ}, c = T0(1 + s f aT)/(S(1 + s f ae)).
  double slide_eps(double T0, double e0, double s, double th) const {
    if (ae == 0.0) return T0 * std::exp(s * f * th) * (1 + s * f * aT) / S;
    const double c = T0 * (1 + s * f * aT) / (S * (1 + s * f * ae));
    return c * std::exp(s * f * th) + (e0 - c) * std::exp(-th / ae);
  }
  bool adhesion_ok(double T, double e) const { return std::abs(S * e - T) <= f * aT * T * (1 + 1e-12); }
  // Tension along the adhesion arc from (T2, ε_a): relaxes towards S ε_a.
  double adhering_tension(double T2, double ea, double ta) const {
    return aT > 0 ? S * ea + (T2 - S * ea) * std::exp(-ta / aT) : S * ea;
  }

  // Entrance sliding arc: the belt slides while adhesion would need |T'| > fT; moves th, T, e
  // to its end.
  void entrance(double& th, double& T, double& e) {
    const double s_in = S * e > T ? 1.0 : -1.0;
    if (aT > 0.0 && !adhesion_ok(T, e)) {
      const double T0 = T, e0 = e;
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
  }

  // Adhesion arc θ_a, with main sliding to T_out after it: θ_a + ln(T_out/T_3)/(direction f)
  // = rest (the wrap after the entrance arc).
  double adhesion_arc(double rest, double T2, double ea, double T_out, double direction) const {
    auto g = [&](double ta) {
      return ta + std::log(T_out / adhering_tension(T2, ea, ta)) / (direction * f) - rest;
    };
    if (!(g(rest) >= 0.0))
      throw InputError("the belt slips: the tension ratio needs more than the wrap", {}, 0, 0,
                       "viscoelastic.tight_N");
    double lo = 0.0, hi = rest;
    if (g(lo) >= 0.0) hi = lo;  // no adhesion arc left: the sliding arc takes the whole rest
    for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
      const double mid = 0.5 * (lo + hi);
      (g(mid) >= 0.0 ? hi : lo) = mid;
    }
    return hi;
  }

  // Main sliding arc from θ = th to the exit at π, tension T3 e^{direction f θ}.
  void main_sliding(double th, double T3, double ea, double direction) {
    p.main_sliding_rad = kPi - th;
    record(th, T3, ea);
    for (double ts = h; ts <= p.main_sliding_rad + 1e-12; ts += h) {
      const double ts_c = std::min(ts, p.main_sliding_rad);
      const double e_s = slide_eps(T3, ea, direction, ts_c);
      record(th + ts_c, T3 * std::exp(direction * f * ts_c), e_s);
      p.max_relative_slip = std::max(p.max_relative_slip, std::abs(e_s - ea));
    }
  }
};

// One pulley of the steady drive, entered with tension T_in and elongation eps_in; leaves with
// T_out. direction = −1 on the driver (tension falls), +1 on the driven pulley.
ViscoelasticPulley march_pulley(const ViscoelasticDriveInput& in, double T_in, double eps_in,
                                double T_out, double direction) {
  const double w = in.omega_rad_s;
  PulleyMarch m{in.belt.S_N, in.friction, w * in.belt.tau_T_s, w * in.belt.tau_eps_s,
                1.0 / in.steps_per_rad, {}};
  double th = 0.0, T = T_in, e = eps_in;
  m.record(th, T, e);
  m.entrance(th, T, e);
  m.p.entrance_sliding_rad = th;
  m.p.adhesion_elongation = e;
  const double T2 = T, ea = e;
  const double ta_end = m.adhesion_arc(kPi - th, T2, ea, T_out, direction);
  m.p.adhesion_rad = ta_end;
  for (double ta = m.h; ta < ta_end; ta += m.h) m.record(th + ta, m.adhering_tension(T2, ea, ta), ea);
  th += ta_end;
  m.main_sliding(th, m.adhering_tension(T2, ea, ta_end), ea, direction);
  return m.p;
}
}  // namespace

ThreeParameterBelt drive_time_belt(double S_N, double omega_rad_s) {
  return {S_N, 0.2 / omega_rad_s, 0.3 / omega_rad_s};
}

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

namespace {
// Residuals of (17a,b), (19a,b), (20a,b) in N. Unknowns: θ_eR, θ_sR, θ_eN, θ_sN, u_R = Sε_R, u_N = Sε_N.
struct SixEquations {
  double TT, TS, f, pT, pe, tT_over_te, E, wrap;  // E = e^{−s_fs/(vτ_ε)}
  std::array<bool, 2> use_entrance_eq{true, true};
  template <typename T>
  bool operator()(const T* x, T* r) const {
    using std::exp;
    const T eR = x[0], sR = x[1], eN = x[2], sN = x[3], uR = x[4], uN = x[5];
    const T aR = T(wrap) - eR - sR, aN = T(wrap) - eN - sN;
    // (17a,b): tension leaving each pulley.
    r[0] = (uR + (TT * exp(-f * eR) - uR) * exp(-f * pT * aR)) * exp(-f * sR) - TS;
    r[1] = (uN + (TS * exp(f * eN) - uN) * exp(-f * pT * aN)) * exp(f * sN) - TT;
    // (19a): S ε entering the driver from (12a) at θ = 0 equals S ε leaving the tight span (18b).
    const double kd = tT_over_te * (pT - 1) / (pe - 1), kn = tT_over_te * (pT + 1) / (pe + 1);
    const T lhsR = TT * kd * (T(1) - exp(f * eR * (pe - 1))) + uR * exp(f * pe * eR);
    const T rhsR = TT * (T(1) + (-(1 - tT_over_te) / (pe + 1) - kn * exp(-f * (pe + 1) * sN)) * E) +
                   uN * exp(-f * pe * sN) * E;
    r[2] = lhsR - rhsR;
    // (19b): the same at the driven pulley, fed by the slack span from the driver.
    const T lhsN = TS * kn * (T(1) - exp(f * eN * (pe + 1))) + uN * exp(f * pe * eN);
    const T rhsN = TS * (T(1) + ((1 - tT_over_te) / (pe - 1) - kd * exp(-f * (pe - 1) * sR)) * E) +
                   uR * exp(-f * pe * sR) * E;
    r[3] = lhsN - rhsN;
    // (20a,b): adhesion starts where |T'| = fT.
    r[4] = use_entrance_eq[0] ? TT * exp(-f * eR) - uR * pT / (pT - 1) : T(0);
    r[5] = use_entrance_eq[1] ? TS * exp(f * eN) - uN * pT / (pT + 1) : T(0);
    return true;
  }
};
}  // namespace

ViscoelasticEquations solve_viscoelastic_equations(const ViscoelasticDriveInput& in) {
  const double f = in.friction, w = in.omega_rad_s;
  if (!(in.belt.tau_T_s > 0 && in.belt.tau_eps_s > 0))
    throw InputError("the six-equation form needs tau_T, tau_eps > 0", {}, 0, 0, "viscoelastic");
  SixEquations eq{in.tight_N, in.slack_N, f, 1.0 / (f * in.belt.tau_T_s * w), 1.0 / (f * in.belt.tau_eps_s * w),
                  in.belt.tau_T_s / in.belt.tau_eps_s,
                  std::exp(-(in.center_distance_mm / in.radius_mm) / (w * in.belt.tau_eps_s)), kPi};
  const double euler = std::log(in.tight_N / in.slack_N) / f;
  std::array<double, 6> x{};
  auto solve = [&] {
    x = {0.0, euler, 0.0, euler, in.tight_N, in.slack_N};
    ceres::Problem problem;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SixEquations, 6, 6>(new SixEquations(eq)), nullptr,
                             x.data());
    for (int i : {0, 1, 2, 3}) {
      problem.SetParameterLowerBound(x.data(), i, 0.0);
      problem.SetParameterUpperBound(x.data(), i, kPi);
    }
    std::vector<int> held;  // an entrance arc without its equation (20) is held at θ_e = 0
    for (int k : {0, 1})
      if (!eq.use_entrance_eq[k]) held.push_back(2 * k);
    if (!held.empty()) problem.SetManifold(x.data(), new ceres::SubsetManifold(6, held));
    ceres::Solver::Options o;
    o.max_num_iterations = 500;
    o.function_tolerance = o.parameter_tolerance = o.gradient_tolerance = 1e-16;
    ceres::Solver::Summary summary;
    ceres::Solve(o, &problem, &summary);
  };
  // Complementarity θ_e ≥ 0 ⟂ (20): try the four active sets; keep the one that solves its
  // equations and, where θ_e = 0, admits adhesion at the entrance (|Sε − T| ≤ fωτ_T T, i.e. the
  // belt would not need to slide there).
  std::array<double, 6> r{};
  bool found = false;
  for (int set = 0; set < 4 && !found; ++set) {
    eq.use_entrance_eq = {(set & 1) == 0, (set & 2) == 0};
    solve();
    eq(x.data(), r.data());
    double worst = 0;
    for (double ri : r) worst = std::max(worst, std::abs(ri));
    bool ok = worst < 1e-6 * in.tight_N;
    const double T_in[2] = {in.tight_N, in.slack_N};
    for (int k : {0, 1})
      if (!eq.use_entrance_eq[k])
        ok = ok && std::abs(x[4 + k] - T_in[k]) <= f * w * in.belt.tau_T_s * T_in[k] * (1 + 1e-9);
    found = ok;
  }
  ViscoelasticEquations out{x[0], x[1], x[2], x[3], x[4] / in.belt.S_N, x[5] / in.belt.S_N, 0.0};
  for (double ri : r) out.max_residual_N = std::max(out.max_residual_N, std::abs(ri));
  if (!found)
    throw core::NumericalError("viscoelastic drive equations (17, 19, 20): no admissible solution "
                               "for any entrance-arc active set (last residual " +
                               core::format_number(out.max_residual_N) + " N)");
  return out;
}

}  // namespace fitlib::belt
