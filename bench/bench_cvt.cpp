// Sorge 2-D CVT contact region (plain main, prints its table): ODE shooting solution of the
// paper's example pulleys against the practical formulary (12a,b).
// For tolerances 1e-4 … 1e-10: wall time of the ODE solve, its thrust error against τ = 1e-12,
// and the gap formulary − ODE. Baseline: the formulary's time, measured in the same run.
#include <chrono>
#include <cmath>
#include <cstdio>

#include "fitlib/belt/cvt.hpp"
#include "fitlib/belt/cvt_ode.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"

using namespace fitlib::belt;
using Clock = std::chrono::steady_clock;

namespace {
using fitlib::core::kPi;
constexpr double kSl = 59000.0;

template <typename F>
double seconds_per_call(F f, double min_total_s = 0.2) {
  int n = 0;
  const auto t0 = Clock::now();
  double t = 0;
  do {
    f();
    ++n;
    t = std::chrono::duration<double>(Clock::now() - t0).count();
  } while (t < min_total_s);
  return t / n;
}
}  // namespace

int main() {
  const CvtContactBelt b = sorge_example_belt();
  const double alpha = b.groove_half_angle_rad;
  for (bool driver : {true, false}) {
    const CvtContactCase c = sorge_example_case(driver);
    CvtOdeOptions o;
    o.keep_profile = false;
    o.tolerance = 1e-12;
    const auto ref = solve_cvt_contact(b, c, o);
    const double eps_in = ref.entry_strain;
    const double T_T = kSl * (driver ? eps_in : c.exit_strain), T_S = kSl * (driver ? c.exit_strain : eps_in);
    volatile double sink = 0;
    const double formulary_s = seconds_per_call([&] {
      sink = sink + (driver ? driver_axial_thrust_N(T_T, alpha, c.wrap_rad) : driven_axial_thrust_N(T_T, T_S, alpha, c.wrap_rad));
    });
    const double formulary_N = driver ? driver_axial_thrust_N(T_T, alpha, c.wrap_rad) : driven_axial_thrust_N(T_T, T_S, alpha, c.wrap_rad);
    std::printf("%s pulley (γ_out %.0f°, ε_out %.5f, Θ = 180°): T_T %.1f N, T_S %.1f N, ODE thrust (τ=1e-12) %.2f N, formulary %.2f N (%+.1f %%), formulary %.2e s/call\n",
                driver ? "driver" : "driven", c.exit_sliding_angle_rad * 180 / kPi, c.exit_strain, T_T, T_S,
                kSl * ref.axial_thrust_per_Sl, formulary_N, 100 * (formulary_N / (kSl * ref.axial_thrust_per_Sl) - 1), formulary_s);
    std::printf("  %-9s %12s %12s %14s %8s %14s\n", "tolerance", "ODE s", "ODE/formula", "thrust error", "shots", "formula − ODE");
    for (double tol : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}) {
      o.tolerance = tol;
      try {
        CvtContactSolution s;
        const double t = seconds_per_call([&] { s = solve_cvt_contact(b, c, o); }, 0.5);
        std::printf("  %-9.0e %12.3f %12.2e %14.2e %8d %13.1f%%\n", tol, t, t / formulary_s,
                    std::abs(s.axial_thrust_per_Sl / ref.axial_thrust_per_Sl - 1), s.shots,
                    100 * (formulary_N / (kSl * s.axial_thrust_per_Sl) - 1));
      } catch (const fitlib::core::NumericalError& e) {
        std::printf("  %-9.0e  shooting did not converge: %s\n", tol, e.what());
      }
    }
  }
}
