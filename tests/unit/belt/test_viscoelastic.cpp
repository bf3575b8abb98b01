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

// The paper's six equations (17, 19, 20) solved with Ceres under θ_e ≥ 0 agree with the march
// through the regions (an independent route to the same steady state).
TEST(ViscoelasticDrive, SixEquationsWithCeresMatchTheMarch) {
  for (auto [tT, te] : {std::pair{0.2, 0.3}, std::pair{0.2, 3.0}, std::pair{0.01, 3.0}, std::pair{0.05, 1.0}}) {
    auto in = fig5(tT, te);
    in.steps_per_rad = 20000;
    const auto m = solve_viscoelastic_drive(in);
    const auto e = solve_viscoelastic_equations(in);
    const double h = 2.0 / in.steps_per_rad;  // the march resolves entrance arcs to a step
    EXPECT_NEAR(e.entrance_R, m.driver.entrance_sliding_rad, h) << tT << " " << te;
    EXPECT_NEAR(e.entrance_N, m.driven.entrance_sliding_rad, h) << tT << " " << te;
    EXPECT_NEAR(e.sliding_R, m.driver.main_sliding_rad, 1e-3) << tT << " " << te;
    EXPECT_NEAR(e.sliding_N, m.driven.main_sliding_rad, 1e-3) << tT << " " << te;
    EXPECT_NEAR(e.eps_R, m.driver.adhesion_elongation, 1e-3 * e.eps_R) << tT << " " << te;
    EXPECT_NEAR(e.eps_N, m.driven.adhesion_elongation, 1e-3 * e.eps_N) << tT << " " << te;
  }
}

// The time simulation of the tension test reproduces the loading closed form (Eqs 3, 4 corrected)
// and shows the paper's unloading facts.
TEST(TensionTest, SimulatedLoadingMatchesClosedFormAndUnloadingSpreadsTheSlidingArc) {
  TensionTestInput in;
  in.belt = {60000.0, 27.0, 40.0};
  in.nodes = 100;
  in.steps_per_phase = 600;
  const auto r = simulate_tension_test(in);
  const double b = tension_test_b_mm(in.d0_mm, in.r_mm, in.f);
  for (std::size_t k = 1; k < r.loading.size(); k += 50)
    EXPECT_NEAR(r.loading[k].span_tension_N / tension_test_loading_N(in.belt, in.v_mm_s, b, r.loading[k].t_s, 0, in.f),
                1.0, 2e-4) << r.loading[k].t_s;
  // Unloading: the sliding/adhesion boundary moves monotonically inward from the span end.
  ASSERT_GT(r.unloading.size(), 10u);
  EXPECT_EQ(r.unloading.front().boundary_rad, 0.0);
  for (std::size_t k = 1; k < r.unloading.size(); ++k)
    EXPECT_GE(r.unloading[k].boundary_rad, r.unloading[k - 1].boundary_rad);
  EXPECT_NEAR(r.unloading.back().boundary_rad, kPi / 2, 1e-12);
  // Hysteresis: at the same elongation the unloading tension is below the loading one.
  const auto& u = r.unloading[r.unloading.size() / 2];
  const double T_load = tension_test_loading_N(in.belt, in.v_mm_s, b, u.elongation_mm / in.v_mm_s, 0, in.f);
  EXPECT_LT(u.span_tension_N, T_load);
}

TEST(TensionTest, InitialUnloadingSlopeIsTheFreeSpansAlone) {
  // At the start of unloading only the free spans relax, so the initial slope dT/dd does not
  // depend on friction (V-belt and overturned flat belt alike, Sec. 3).
  auto slope = [](double f) {
    TensionTestInput in;
    in.f = f;
    in.nodes = 100;
    in.steps_per_phase = 1200;
    const auto r = simulate_tension_test(in);
    const auto& a = r.unloading[0];
    const auto& c = r.unloading[1];
    return (c.span_tension_N - a.span_tension_N) / (c.elongation_mm - a.elongation_mm);
  };
  EXPECT_NEAR(slope(0.3) / slope(0.12), 1.0, 0.02);
}
