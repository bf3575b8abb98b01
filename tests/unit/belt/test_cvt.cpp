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
