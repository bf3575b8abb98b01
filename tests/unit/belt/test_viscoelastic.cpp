// Sorge–Cammalleri three-parameter belt: Eq. (4) (typo decided), relaxation, the steady drive's
// findings (τ_T = τ_ε is elastic-like; entrance sliding only for τ_T ≪ τ_ε; a viscous cord lowers
// the sliding speed).
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/belt/viscoelastic.hpp"
#include "fitlib/core/units.hpp"

using namespace fitlib::belt;
using fitlib::core::kPi;

TEST(TensionTest, CorrectedEq4SolvesTheConstitutiveLawAndThePrintedOneDoesNot) {
  const ThreeParameterBelt m{60000.0, 27.0, 40.0};  // measured values of the paper
  const double v = 10.0 / 60.0, f = 0.12, b = tension_test_b_mm(250.0, 39.0, f);
  std::vector<double> t, eps;
  for (int k = 0; k <= 2000; ++k) {
    t.push_back(0.1 * k);
    eps.push_back(v * t.back() / b);  // θ = 0 (Eq 3)
  }
  const auto T = integrate_three_parameter(m, t, eps);
  double worst_corrected = 0, worst_printed = 0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    worst_corrected = std::max(worst_corrected, std::abs(T[k] / tension_test_loading_N(m, v, b, t[k], 0, f) - 1));
    worst_printed = std::max(worst_printed, std::abs(T[k] / tension_test_loading_as_printed_N(m, v, b, t[k], 0, f) - 1));
  }
  EXPECT_LT(worst_corrected, 1e-10);
  EXPECT_GT(worst_printed, 1e-2);
}

TEST(TensionTest, RelaxationDecaysWithTauT) {
  const ThreeParameterBelt m{60000.0, 27.0, 40.0};
  // Hold ε after a fast ramp: the integrated force relaxes to Sε with time constant τ_T.
  std::vector<double> t{0.0, 1e-6}, eps{0.0, 0.01};
  for (int k = 1; k <= 100; ++k) {
    t.push_back(k * 1.0);
    eps.push_back(0.01);
  }
  const auto T = integrate_three_parameter(m, t, eps);
  for (std::size_t k = 2; k < t.size(); ++k)
    EXPECT_NEAR(T[k], relaxation_N(m, T[1], 600.0, t[k] - 1e-6), 1e-6 * T[1]);
}

namespace {
ViscoelasticDriveInput fig5(double tau_T_w, double tau_eps_w) {
  ViscoelasticDriveInput in;  // r = 40 mm, d0 = 250 mm, f = 0.5, T_T/T_S = 2.5
  in.omega_rad_s = 100.0;
  in.belt.tau_T_s = tau_T_w / in.omega_rad_s;
  in.belt.tau_eps_s = tau_eps_w / in.omega_rad_s;
  in.tight_N = 500.0;
  in.slack_N = 200.0;
  return in;
}
}  // namespace

TEST(ViscoelasticDrive, EqualTimesBehaveElastically) {
  const auto d = solve_viscoelastic_drive(fig5(0.5, 0.5));
  const double euler = std::log(2.5) / 0.5;  // Euler–Grashof sliding arc
  EXPECT_NEAR(d.driver.main_sliding_rad, euler, 1e-3);
  EXPECT_NEAR(d.driven.main_sliding_rad, euler, 1e-3);
  EXPECT_EQ(d.driver.entrance_sliding_rad, 0.0);
  EXPECT_EQ(d.driven.entrance_sliding_rad, 0.0);
  for (const auto* p : {&d.driver, &d.driven})
    for (std::size_t k = 0; k < p->T_N.size(); ++k) EXPECT_NEAR(p->T_N[k], 60000.0 * p->eps[k], 1e-6 * p->T_N[k]);
}

TEST(ViscoelasticDrive, EntranceSlidingOnlyWhenTauTMuchSmallerThanTauEps) {
  const auto mild = solve_viscoelastic_drive(fig5(0.2, 0.3));  // the paper's drive estimate
  EXPECT_EQ(mild.driver.entrance_sliding_rad, 0.0);
  EXPECT_EQ(mild.driven.entrance_sliding_rad, 0.0);
  const auto strong = solve_viscoelastic_drive(fig5(0.01, 3.0));
  EXPECT_GT(strong.driver.entrance_sliding_rad + strong.driven.entrance_sliding_rad, 0.0);
}

TEST(ViscoelasticDrive, ViscousCordLowersSlidingSpeed) {
  const auto elastic = solve_viscoelastic_drive(fig5(0.2, 0.2));
  const auto viscous = solve_viscoelastic_drive(fig5(0.2, 3.0));
  EXPECT_LT(viscous.driver.max_relative_slip, 0.8 * elastic.driver.max_relative_slip);
  EXPECT_LT(viscous.driven.max_relative_slip, 0.8 * elastic.driven.max_relative_slip);
}
