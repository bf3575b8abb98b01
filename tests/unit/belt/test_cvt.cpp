// Sorge CVT formulary: the totals (12a,b) are the integrals of the distributions (11) with the
// paper's constants (ξ_R = 2.2, ξ_N = 1.5, n = 5, Θ_seat = π/6, Θ_unseat = π/18).
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/belt/cvt.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"

using namespace fitlib::belt;
using fitlib::core::kPi;

namespace {
template <typename F>
double simpson(F f, double a, double b, int n = 20000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4 : 2);
  return s * h / 3;
}
}  // namespace

TEST(CvtFormulary, TotalsAreIntegralsOfTheDistributions) {
  const double alpha = 12.8 * kPi / 180, T_T = 900, T_S = 350;
  for (double wrap : {2.4, kPi, 3.8}) {
    const double R = simpson([&](double t) { return driver_axial_thrust_density_N(t, wrap, T_T, alpha); }, 0, wrap);
    EXPECT_NEAR(R / driver_axial_thrust_N(T_T, alpha, wrap), 1.0, 1e-6) << wrap;
    const double N = simpson([&](double t) { return driven_axial_thrust_density_N(t, wrap, T_T, T_S, alpha); }, 0, wrap);
    EXPECT_NEAR(N / driven_axial_thrust_N(T_T, T_S, alpha, wrap), 1.0, 1e-6) << wrap;
  }
}

TEST(CvtFormulary, DrivenUnseatingBumpReachesHalfTheTightTension) {
  // kx_max ≈ ε_out/2: the driven density at the end of the inner region is T_T/(4 tan α).
  const double alpha = 0.2, wrap = 3.0, T_T = 800, T_S = 300;
  const double theta = wrap - kPi / 18;
  EXPECT_NEAR(driven_axial_thrust_density_N(theta - 1e-12, wrap, T_T, T_S, alpha), T_T / (4 * std::tan(alpha)), 1e-6);
  EXPECT_NEAR(driven_axial_thrust_density_N(theta + 1e-12, wrap, T_T, T_S, alpha), T_T / (4 * std::tan(alpha)), 1e-6);
}

TEST(CvtFormulary, ShortWrapIsAnError) {
  EXPECT_THROW(driver_axial_thrust_N(100, 0.2, 0.5), fitlib::core::InputError);
}

#include "fitlib/belt/drive.hpp"
#include "fitlib/belt/load_cycle.hpp"

namespace {
// The CVT of the paper (§IV): S_l = 59000 N, S_f = 6500 N·mm², E_z h/w = 21 N/mm², α = 12.8°, μ = 0.4,
// equal wrap radii 39.5 mm from the belt length 758 mm and centre distance 255 mm.
DriveCase sorge_cvt(double torque_Nm, double slack_N) {
  DriveCase c;
  c.geometry = make_two_pulley_geometry({"driver", 39.5, PulleyRole::driver}, {"driven", 39.5, PulleyRole::driven}, 255.0);
  c.span_tension_N = span_tensions(c.geometry, {torque_Nm, TensionRule::slack, slack_N});
  c.friction = 0.4;
  c.belt.wedge_half_angle_rad = 12.8 * kPi / 180;
  c.belt.width_mm = 15.5;
  c.belt.height_mm = 8.0;
  c.belt.c_N = 59000;
  c.belt.EI_Nmm2 = 6500;
  c.belt.k1_MPa = 10 * std::tan(c.belt.wedge_half_angle_rad) * 21.0;
  c.belt.density_kg_m3 = 0.0;
  return c;
}
}  // namespace

TEST(CvtThrust, OneDimensionalThrustWithoutSlidingIsHalfFPThetaCot) {
  // No torque, no bending zones: F and γ = 180° are constant over the wrap, so the thrust is
  // ½ F cot(α + arctan μ) Θ exactly.
  auto c = sorge_cvt(0.0, 400.0);
  LoadCycleOptions o;
  o.effects = {false, false, false, false};
  const auto cycle = compute_load_cycle(c, o);
  const double expected = 0.5 * 400.0 / std::tan(12.8 * kPi / 180 + std::atan(0.4)) * kPi;
  EXPECT_NEAR(axial_thrust_N(cycle, c.belt, 0), expected, 1e-3 * expected);
}

// How far the formulary (12a,b), fitted to Sorge's 2-D solutions, is from the project's 1-D
// V-belt solution (full ODE arcs, bending zones) for the paper's CVT: printed, and bounded.
TEST(CvtThrust, FormularyAgainstOneDimensionalSolution) {
  const double alpha = 12.8 * kPi / 180;
  for (double torque : {5.0, 10.0, 15.0}) {
    auto c = sorge_cvt(torque, 250.0);
    LoadCycleOptions o;
    o.effects = {true, false, true, true};
    const auto cycle = compute_load_cycle(c, o);
    const double T_S = c.span_tension_N[0], T_T = c.span_tension_N[1];
    const double ode_R = axial_thrust_N(cycle, c.belt, 0), ode_N = axial_thrust_N(cycle, c.belt, 1);
    const double fR = driver_axial_thrust_N(T_T, alpha, kPi), fN = driven_axial_thrust_N(T_T, T_S, alpha, kPi);
    std::printf("  torque %4.1f N·m: driver formulary %7.1f N, 1-D %7.1f N (%+.0f %%); driven %7.1f N, 1-D %7.1f N (%+.0f %%)\n",
                torque, fR, ode_R, 100 * (fR / ode_R - 1), fN, ode_N, 100 * (fN / ode_N - 1));
    EXPECT_GT(fR / ode_R, 0.5);
    EXPECT_LT(fR / ode_R, 2.0);
    EXPECT_GT(fN / ode_N, 0.5);
    EXPECT_LT(fN / ode_N, 2.0);
  }
}
