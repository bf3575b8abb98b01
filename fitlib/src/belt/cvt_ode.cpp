// Sorge's 2-D contact-region ODE system (Eqs 3–11; docs/belt.md, "Sorge 2-D CVT: contact-region
// ODE"), shooting from the exit. Reconstruction notes ([DERIVED] = not printed legibly in the source, derived from the
// paper's own definitions; docs/belt.md "Sorge 2-D CVT: contact-region ODE" lists them):
//  - Sliding direction (4): γ(Z) is the direction of the belt's sliding velocity in the plane
//    (radially inward, forward), a = (1 + ε) sin χ, b = (1 + ε) cos χ − κ(1 − x)[1 + ZH(m − 1)]:
//    tan γ = b/a is Eq (4) with χ' + sσ' = m − 1 from (10); the quadrant is that of (a, b)
//    [DERIVED: the friction terms of (5–6) then oppose the sliding, checked in the tests].
//  - Wall kernels (8–9): 1/(1 − tan β/(cos²α tan γ)) = (sin α + f cos γ_w cos α)/(tan α(cos α −
//    f cos γ_w sin α)) [DERIVED from (5–7)], which is regular at γ = 0°, 90°, 180°; γ_w has the
//    direction (a, b cos α) (tan γ_w = cos α tan γ, same quadrant).
//  - Eq (11) [DERIVED, garbled in the source]: from m = (M/S_f + 1/r_fact) g, g = dc/dθ =
//    r∞(1 − x)/cos χ, g'/g = tan χ (χ' − 1) by (3), and dM/dc = S − M_f with the friction moment
//    M_f = ∫ z (dF'_w)_∥ cos χ/r̄ (the paper's text):
//      m' = m tan χ (χ' − 1) + (1/P)((1 − x)/cos χ)² [σ − H k x cos χ ∫₀¹ Z w(Z) K_∥(Z) dZ],
//    P = S_f/(S_l r∞²) (the figures' "S_f/(S_l r²)").
//  - (9) and (10) are linear in χ', σ': σ' = (εm − R)/(1 + sε), χ' = m − 1 − sσ' [DERIVED].
//  - End shear (b5–b6): with x = 0, R = 0, so 1 + χ' = m/(1 + sε) and σ = ±√(Pε(1 + sε))(1 + x'')
//    becomes σ = ±m √(Pε/(1 + sε)) [DERIVED; x'' ≈ χ' at x = 0 to the paper's order].
//  - κ from the exit (the paper: "calculable ... at the exit point"): at x = 0, Z = 0,
//    κ = (1 + ε_out)(cos χ_out − sin χ_out tan γ_out) [DERIVED from (4)].
#include "fitlib/belt/cvt_ode.hpp"

#include <array>
#include <cmath>
#include <string>

#include <Eigen/Dense>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/numeric/odeint.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::belt {
namespace {
using core::kPi;
using State = std::array<double, 6>;  // x, χ, ε, σ, m, ∫F'_axial dθ / S_l
struct Blowup {};                     // a shot left the physical range (|χ| → 90°, x ≫ 0)

// Gauss–Legendre on [z0, z1] for the five smooth pieces of the Z-integrands.
template <typename F>
void gauss_on(double z0, double z1, F&& add) {
  using G = boost::math::quadrature::gauss<double, 8>;
  const double half = 0.5 * (z1 - z0), mid = 0.5 * (z0 + z1);
  const auto& xs = G::abscissa();
  const auto& ws = G::weights();
  for (std::size_t i = 0; i < xs.size(); ++i) {
    add(mid - half * xs[i], half * ws[i]);
    add(mid + half * xs[i], half * ws[i]);
  }
}
}  // namespace

CvtWallKernels cvt_wall_kernels(const CvtContactBelt& b, double x, double chi, double eps, double m,
                                double kappa) {
  const double f = b.friction, al = b.groove_half_angle_rad;
  const double ca = std::cos(al), sa = std::sin(al), ta = std::tan(al);
  const double cc = std::cos(chi), tc = std::tan(chi);
  const double a = (1 + eps) * std::sin(chi);
  const double b0 = (1 + eps) * cc - kappa * (1 - x), b1 = kappa * (1 - x) * b.H * (m - 1);
  CvtWallKernels k{0, 0, 0, 0};
  auto add = [&](double Z, double wq) {
    const double bz = b0 - b1 * Z;
    const double rho = std::hypot(a, bz * ca);
    // No sliding at this Z (a = b = 0): the friction direction is undefined; it is a single point.
    const double cw = rho > 0 ? a / rho : 0.0, sw = rho > 0 ? bz * ca / rho : 0.0;
    const double den = ta * (ca - f * cw * sa);
    const double w = (1 - Z * b.H * cc / (1 - x)) / (1 - 2 * Z * b.W * ta);
    const double par = (sa * tc + f * (cw * ca * tc + sw)) / den;
    k.parallel += wq * w * par;
    k.perpendicular += wq * w * (sa + f * (cw * ca - sw * tc)) / den;
    k.moment += wq * Z * w * par;
    k.axial += wq * (1 - x - Z * b.H * cc) / (2 * ta * cc * (1 - 2 * Z * b.W * ta));
  };
  // The friction direction turns where b(Z) changes sign (b is linear in Z): split there so each
  // piece is smooth.
  const double z_star = b1 != 0 ? b0 / b1 : -1.0;
  if (z_star > 0 && z_star < 1) {
    gauss_on(0, z_star, add);
    gauss_on(z_star, 1, add);
  } else {
    gauss_on(0, 1, add);
  }
  return k;
}

namespace {
struct Contact {
  CvtContactBelt b;
  double kappa;
  // d/dθ of the state (θ from entrance to exit).
  State rates(const State& y) const {
    const double x = y[0], chi = y[1], eps = y[2], sig = y[3], m = y[4];
    if (!(std::abs(chi) < 1.2 && x > -0.2 && x < 0.5 && std::abs(m) < 1e4 && std::abs(eps) < 1 &&
          std::isfinite(sig)))
      throw Blowup{};
    const auto K = cvt_wall_kernels(b, x, chi, eps, m, kappa);
    const double R = b.k * x * (1 - x) * K.perpendicular, Q = b.k * x * (1 - x) * K.parallel;
    const double cc = std::cos(chi), tc = std::tan(chi);
    const double dsig = (eps * m - R) / (1 + b.s * eps);                         // (9) with (10)
    const double dchi = m - 1 - b.s * dsig;                                       // (10)
    const double deps = Q - sig * (1 + dchi);                                     // (8)
    const double g = (1 - x) / cc;
    const double dm = m * tc * (dchi - 1) + g * g / b.P * (sig - b.H * b.k * x * cc * K.moment);  // (11)
    return {(1 - x) * tc, dchi, deps, dsig, dm, b.k * x * K.axial};              // (3), (7)
  }
};

double end_shear(const CvtContactBelt& b, double eps, double m) {
  return m * std::sqrt(b.P * eps / (1 + b.s * eps));
}

using Vec = Eigen::VectorXd;
using Path = std::vector<std::pair<double, State>>;  // (θ, state)

struct Shooter {
  CvtContactBelt b;
  CvtContactCase c;
  CvtOdeOptions o;
  int shots = 0;

  double kappa(double chi_out) const {
    return (1 + c.exit_strain) * (std::cos(chi_out) - std::sin(chi_out) * std::tan(c.exit_sliding_angle_rad));
  }
  // Integrates the contact ODE from θ0 over `length` (backward when `backward`): the state y is
  // advanced in place; the path (θ, state) is appended when asked.
  void integrate(State& y, double kappa, double theta0, double length, bool backward, Path* path) {
    namespace odeint = boost::numeric::odeint;
    ++shots;
    const Contact sys{b, kappa};
    const double dir = backward ? -1.0 : 1.0;
    long calls = 0;
    auto rhs = [&](const State& s, State& d, double) {
      // A stiff or non-finite shot is abandoned rather than stepped forever.
      if (++calls > 200000) throw Blowup{};
      d = sys.rates(s);
      for (double v : d)
        if (!std::isfinite(v)) throw Blowup{};
      if (backward)
        for (double& v : d) v = -v;
    };
    auto observe = [&](const State& s, double t) {
      if (path) path->emplace_back(theta0 + dir * t, s);
    };
    auto stepper = odeint::make_controlled(o.tolerance, o.tolerance, odeint::runge_kutta_dopri5<State>());
    odeint::integrate_adaptive(stepper, rhs, y, 0.0, length, 1e-3, observe);
  }
  // Shooting from the exit; with N > 1 segments (multiple shooting) every segment is integrated
  // backward (the stable direction) from its own start state: u = (χ_out,
  // m_out, then the states (x, χ, ε, σ, m) at the nodes θ_j = Θ(1 − j/N), j = 1..N−1); the
  // residuals are the jumps at the nodes (scaled) and the entrance conditions.
  State node_state(const Vec& u, int j) const {
    return {u[2 + 5 * (j - 1)], u[3 + 5 * (j - 1)], u[4 + 5 * (j - 1)], u[5 + 5 * (j - 1)], u[6 + 5 * (j - 1)], 0.0};
  }
  Vec multi(const Vec& u, int N, std::vector<Path>* paths = nullptr, double* thrust = nullptr, State* entry = nullptr) {
    const double seg = c.wrap_rad / N, kap = kappa(u[0]);
    const double scale[5] = {c.exit_strain / b.k, 0.1, c.exit_strain, std::sqrt(b.P * c.exit_strain), 1.0};
    Vec r(2 + 5 * (N - 1));
    if (thrust) *thrust = 0;
    for (int j = 0; j < N; ++j) {
      Path* p = paths ? &(*paths)[j] : nullptr;
      State y;
      if (j == 0) {
        if (!(u[0] < 0)) throw Blowup{};  // γ_out in (90°, 270°): the belt leaves the groove
        y = {0.0, u[0], c.exit_strain, -end_shear(b, c.exit_strain, u[1]), u[1], 0.0};
      } else {
        y = node_state(u, j);
      }
      integrate(y, kap, c.wrap_rad - j * seg, seg, true, p);
      if (thrust) *thrust -= y[5];
      if (j + 1 < N) {
        const State n = node_state(u, j + 1);
        for (int i = 0; i < 5; ++i) r[5 * j + i] = (y[i] - n[i]) / scale[i];
      } else {
        if (entry) *entry = y;
        r[5 * j] = y[0] * b.k / c.exit_strain;
        r[5 * j + 1] = (y[3] - end_shear(b, y[2], y[4])) / std::sqrt(b.P * c.exit_strain);
      }
    }
    return r;
  }
  // Nodes of an N-segment shot from the exit unknowns (χ_out, m_out).
  Vec to_nodes(const Vec& v, int N) {
    Vec w(2 + 5 * (N - 1));
    w[0] = v[0], w[1] = v[1];
    State y{0.0, v[0], c.exit_strain, -end_shear(b, c.exit_strain, v[1]), v[1], 0.0};
    for (int j = 1; j < N; ++j) {
      integrate(y, kappa(v[0]), c.wrap_rad - (j - 1) * c.wrap_rad / N, c.wrap_rad / N, true, nullptr);
      for (int i = 0; i < 5; ++i) w[2 + 5 * (j - 1) + i] = y[i];
    }
    return w;
  }
  // Damped Newton with a forward-difference Jacobian; returns the residual norm reached.
  template <typename F>
  double newton(Vec& u, F&& residual) {
    Vec r = residual(u);
    for (int it = 0; it < o.max_newton_iterations && r.norm() > o.shooting_tolerance; ++it) {
      Eigen::MatrixXd J(r.size(), u.size());
      for (int j = 0; j < u.size(); ++j) {
        Vec up = u;
        const double h = 1e-7 * std::max(std::abs(u[j]), 1e-2);
        up[j] += h;
        J.col(j) = (residual(up) - r) / h;
      }
      const Vec d = J.fullPivLu().solve(-r);
      if (!d.allFinite()) break;
      bool improved = false;
      for (double lam = 1.0; lam > 1e-6 && !improved; lam *= 0.5) {
        try {
          const Vec t = u + lam * d;
          const Vec rt = residual(t);
          if (rt.norm() < r.norm()) u = t, r = rt, improved = true;
        } catch (const Blowup&) {
        }
      }
      if (!improved) break;
    }
    return r.norm();
  }
};

CvtContactSolution solve(const CvtContactBelt& b, const CvtContactCase& c, const CvtOdeOptions& o);

void check_inputs(const CvtContactBelt& b, const CvtContactCase& c) {
  auto bad = [](const std::string& what, const char* key) { throw core::InputError(what, {}, 0, 0, key); };
  if (!(b.groove_half_angle_rad > 0 && b.groove_half_angle_rad < kPi / 2)) bad("groove half-angle must lie in (0, 90) deg", "cvt.groove_half_angle_deg");
  if (!(b.friction >= 0 && b.friction * std::tan(b.groove_half_angle_rad) < 1)) bad("friction must lie in [0, cot α): self-locking groove", "cvt.friction");
  if (!(b.k > 0 && b.P > 0 && b.s >= 0 && b.H >= 0 && b.H < 1 && b.W >= 0 && 2 * b.W * std::tan(b.groove_half_angle_rad) < 1))
    bad("belt groups need k > 0, P > 0, s >= 0, 0 <= H < 1 and a positive bottom width", "cvt.belt");
  if (!(c.exit_strain > 0 && c.exit_strain < 0.5)) bad("exit strain must lie in (0, 0.5)", "cvt.exit_strain");
  if (!(c.exit_sliding_angle_rad > kPi / 2 && c.exit_sliding_angle_rad < 1.5 * kPi)) bad("exit sliding angle must lie in (90, 270) deg", "cvt.exit_sliding_angle_deg");
  if (!(c.wrap_rad > 0.05 && c.wrap_rad < 2 * kPi)) bad("wrap must lie in (0.05, 2π) rad", "cvt.wrap_deg");
}
}  // namespace

CvtContactSolution solve_cvt_contact(const CvtContactBelt& b, const CvtContactCase& c, const CvtOdeOptions& o) {
  check_inputs(b, c);
  try {
    return solve(b, c, o);
  } catch (const Blowup&) {
    throw core::NumericalError("CVT contact shooting left the physical range (|χ| → 90° or x ≫ 0)");
  }
}

namespace {
[[noreturn]] void shooting_failed(double wrap, double res) {
  throw core::NumericalError("CVT contact shooting did not converge at wrap " + core::format_number(wrap * 180 / kPi) +
                             " deg (residual " + core::format_number(res) + ")");
}

// Newton's first guess for a short wrap: the best of a coarse grid over (χ_out, m_out).
Vec coarse_exit_guess(Shooter& sh) {
  Vec u2(2);
  u2 << -0.1, 1.0;
  double best = HUGE_VAL;
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) {
      Vec t(2);
      t << -0.01 * std::pow(1.6, i), -2.0 + 1.0 * j;
      try {
        const double n = sh.multi(t, 1).norm();
        if (n < best) best = n, u2 = t;
      } catch (const Blowup&) {
      }
    }
  }
  return u2;
}

// The shooting unknowns at the full wrap: u, its segment count N and residual.
struct WrapSolution {
  Vec u;
  int N = 1;
  double residual;
};

// Continuation in the wrap from sh.c.wrap_rad to wrap_end with a secant predictor; the step
// halves when Newton fails. Single shooting from the exit while it converges; once e^{λΘ}
// nears 1e15 it loses all digits (the driven example beyond ~120°), and the wrap is cut into N
// segments, each shot backward from its end (multiple shooting; forward shots from the
// entrance diverge).
WrapSolution continue_in_wrap(Shooter& sh, WrapSolution s, double wrap_end, double accept) {
  Vec u_prev = s.u;
  double wrap = sh.c.wrap_rad, wrap_prev = wrap, step = sh.o.continuation_step_rad;
  while (wrap < wrap_end) {
    const double next = std::min(wrap_end, wrap + step);
    Vec t = s.u;
    if (wrap > wrap_prev) t += (s.u - u_prev) * (next - wrap) / (wrap - wrap_prev);
    sh.c.wrap_rad = next;
    double r = HUGE_VAL;
    try {
      r = sh.newton(t, [&](const Vec& v) { return sh.multi(v, s.N); });
    } catch (const Blowup&) {
    }
    if (r <= accept) {
      u_prev = s.u, wrap_prev = wrap, s.u = t, wrap = next, s.residual = r;
      step = std::min(step * 1.5, sh.o.continuation_step_rad);
    } else if (s.N == 1 && step < 0.05) {
      s.N = std::max(2, static_cast<int>(std::ceil(wrap_end / 0.8)));
      sh.c.wrap_rad = wrap;
      s.u = sh.to_nodes(s.u, s.N), u_prev = s.u, wrap_prev = wrap, step = 0.05;
    } else if ((step *= 0.5) < 1e-4) {
      shooting_failed(next, r);
    }
  }
  return s;
}

// The solution at the full wrap: exit unknowns, thrust, entry strain and the profile.
CvtContactSolution solution_of(Shooter& sh, const WrapSolution& s, double wrap_rad) {
  CvtContactSolution sol;
  sol.exit_penetration_angle_rad = s.u[0];
  sol.exit_moment = s.u[1];
  sol.kappa = sh.kappa(s.u[0]);
  sol.residual = s.residual;
  sh.c.wrap_rad = wrap_rad;
  std::vector<Path> paths(s.N);
  State entry{};
  sh.multi(s.u, s.N, sh.o.keep_profile ? &paths : nullptr, &sol.axial_thrust_per_Sl, &entry);
  sol.entry_strain = entry[2];
  for (int j = s.N - 1; j >= 0; --j) {  // profile entrance → exit
    const Path& p = paths[j];
    for (auto it = p.rbegin(); it != p.rend(); ++it) {
      if (!sol.theta.empty() && std::abs(it->first - sol.theta.back()) < 1e-14) continue;
      sol.theta.push_back(it->first), sol.x.push_back(it->second[0]), sol.chi.push_back(it->second[1]),
          sol.eps.push_back(it->second[2]), sol.sigma.push_back(it->second[3]), sol.m.push_back(it->second[4]);
    }
  }
  sol.shots = sh.shots;
  return sol;
}

CvtContactSolution solve(const CvtContactBelt& b, const CvtContactCase& c, const CvtOdeOptions& o) {
  // 1. Short wrap, single shooting from the exit (the paper's method).
  CvtContactCase short_case = c;
  short_case.wrap_rad = std::min(c.wrap_rad, 0.5);
  Shooter sh{b, short_case, o};
  WrapSolution s{coarse_exit_guess(sh)};
  s.residual = sh.newton(s.u, [&](const Vec& u) { return sh.multi(u, 1); });
  const double accept = std::max(o.accept_residual, 30 * o.tolerance);  // integration noise
  if (!(s.residual <= accept)) shooting_failed(short_case.wrap_rad, s.residual);
  // 2. Continuation to the full wrap.
  return solution_of(sh, continue_in_wrap(sh, s, c.wrap_rad, accept), c.wrap_rad);
}
}  // namespace

CvtContactBelt sorge_example_belt() { return {}; }

CvtContactCase sorge_example_case(bool driver) {
  CvtContactCase c;
  c.exit_strain = (driver ? 250.0 : 500.0) / 59000.0;
  c.exit_sliding_angle_rad = (driver ? 191.0 : 184.0) * kPi / 180;
  return c;
}

}  // namespace fitlib::belt
