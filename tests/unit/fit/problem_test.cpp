// Residual definitions, weights, transforms and their Jacobian.
#include <gtest/gtest.h>

#include "fit_testing.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/fit/problem.hpp"

using namespace fitlib;
using namespace fitlib::fit::testing;

namespace {

data::DynamicTestTable two_rows() {
  data::DynamicTestTable t;
  data::DynamicTestRow a;
  a.condition.frequency_Hz = 1.0;
  a.storage_MPa = 2.0;
  a.loss_MPa = 0.5;
  a.weight = 4.0;
  data::DynamicTestRow b = a;
  b.condition.frequency_Hz = 10.0;
  b.storage_MPa = 3.0;
  b.loss_MPa = 1.0;
  b.weight = 1.0;
  b.has_mean_modulus = true;
  b.mean_modulus_MPa = 1.5;
  t.rows = {a, b};
  return t;
}

}  // namespace

TEST(Residuals, Log10WithRowAndComponentWeightsByHand) {
  const auto model = prony(1);
  const std::vector<double> p = prony_parameters(1.0, {2.0}, {0.1});
  const auto table = two_rows();
  fit::FitOptions o;
  o.storage_weight = 9.0;
  o.loss_weight = 1.0;
  o.mean_weight = 0.25;
  fit::Problem pb(model, table, o, p);
  ASSERT_EQ(pb.num_residuals(), 5);  // mean only for the row that carries one
  std::vector<double> r(5);
  ASSERT_TRUE(pb.evaluate(p, r.data(), nullptr));
  int e = 0;
  for (int row = 0; row < 2; ++row) {
    const auto& rr = table.rows[row];
    const auto m = model->moduli(p.data(), rr.condition);
    EXPECT_NEAR(r[e++], std::sqrt(rr.weight * 9.0) * std::log10(m.storage / rr.storage_MPa), 1e-14);
    EXPECT_NEAR(r[e++], std::sqrt(rr.weight * 1.0) * std::log10(m.loss / rr.loss_MPa), 1e-14);
    if (rr.has_mean_modulus) {
      EXPECT_NEAR(r[e++], std::sqrt(rr.weight * 0.25) * std::log10(m.mean / rr.mean_modulus_MPa),
                  1e-14);
    }
  }
}

TEST(Residuals, RelativeKind) {
  const auto model = prony(1);
  const std::vector<double> p = prony_parameters(1.0, {2.0}, {0.1});
  const auto table = two_rows();
  fit::FitOptions o;
  o.residual = fit::ResidualKind::relative;
  fit::Problem pb(model, table, o, p);
  std::vector<double> r(pb.num_residuals());
  ASSERT_TRUE(pb.evaluate(p, r.data(), nullptr));
  const auto m = model->moduli(p.data(), table.rows[1].condition);
  EXPECT_NEAR(r[2], (m.storage - 3.0) / 3.0, 1e-14);
  EXPECT_NEAR(r[3], (m.loss - 1.0) / 1.0, 1e-14);
  EXPECT_NEAR(r[4], (m.mean - 1.5) / 1.5, 1e-14);
}

// d r / d x with x = ln p for log-transformed parameters, against central differences in x.
TEST(Residuals, JacobianInFittedCoordinatesMatchesFiniteDifferences) {
  const auto model = prony(3);
  const std::vector<double> p = prony_parameters(1.0, {2.0, 0.5, 3.0}, {0.01, 0.3, 5.0});
  const auto table = synthetic_table(*model, prony_parameters(1.2, {1.0, 1.0, 2.0}, {0.02, 0.2, 3.0}),
                                     log_frequencies(0.01, 100.0, 9), 0.0, 1);
  fit::Problem pb(model, table, {}, p);
  const int m = pb.num_residuals(), n = pb.num_free();
  std::vector<double> r(m), jac(static_cast<std::size_t>(m) * n);
  ASSERT_TRUE(pb.evaluate(p, r.data(), jac.data()));
  const Eigen::VectorXd x = pb.to_x(p);
  for (int k = 0; k < n; ++k) {
    const double h = 1e-6;
    Eigen::VectorXd xp = x, xm = x;
    xp[k] += h;
    xm[k] -= h;
    std::vector<double> pp = p, pm = p, rp(m), rm(m);
    pb.from_x(xp.data(), pp);
    pb.from_x(xm.data(), pm);
    ASSERT_TRUE(pb.evaluate(pp, rp.data(), nullptr));
    ASSERT_TRUE(pb.evaluate(pm, rm.data(), nullptr));
    for (int i = 0; i < m; ++i)
      EXPECT_NEAR(jac[static_cast<std::size_t>(i) * n + k], (rp[i] - rm[i]) / (2 * h), 1e-7)
          << "residual " << i << " parameter " << k;
  }
}

// A zero loss modulus has no log: its residual is absolute, (E″_model − 0)/(E′·ln 10).
TEST(Residuals, ZeroLossUsesAnAbsoluteResidualOnTheStorageScale) {
  const auto model = prony(1);
  const std::vector<double> p = prony_parameters(1.0, {2.0}, {0.1});
  auto table = two_rows();
  table.rows[0].loss_MPa = 0.0;
  fit::Problem pb(model, table, {}, p);
  std::vector<double> r(pb.num_residuals());
  ASSERT_TRUE(pb.evaluate(p, r.data(), nullptr));
  const auto m = model->moduli(p.data(), table.rows[0].condition);
  EXPECT_NEAR(r[1], 2.0 * m.loss / (2.0 * std::log(10.0)), 1e-14);  // sqrt(weight 4) = 2
  EXPECT_TRUE(pb.entries()[1].absolute);
}

TEST(Residuals, WlfC2LowerBoundKeepsTheDataOnThePhysicalSideOfThePole) {
  const auto model = model::make_model(
      "prony", {{"terms", 1}, {"temperature_law", "wlf"}, {"reference_C", 20.0}});
  auto table = two_rows();
  table.rows[0].condition.temperature_C = -60.0;  // T_ref − T = 80 °C
  table.rows[1].condition.temperature_C = 40.0;
  std::vector<double> p = model->default_parameters();
  const int c2 = core::find_parameter(model->parameters(), "C2");
  ASSERT_GE(c2, 0);
  p[c2] = 50.0;  // start beyond the pole: clamped inside
  fit::Problem pb(model, table, {}, p);
  EXPECT_DOUBLE_EQ(pb.lower(c2), 81.0);
  EXPECT_GT(pb.natural()[c2], 81.0);
  bool said = false;
  for (const auto& n : pb.notes()) said = said || n.find("pole") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(Residuals, BadRowsAreInputErrors) {
  const auto model = prony(1);
  auto table = two_rows();
  table.rows[1].loss_MPa = -1.0;
  EXPECT_THROW(fit::Problem(model, table, {}, model->default_parameters()), core::InputError);
  table = two_rows();
  table.rows[0].weight = std::nan("");
  EXPECT_THROW(fit::Problem(model, table, {}, model->default_parameters()), core::InputError);
}

TEST(Summary, RangesOfTheData) {
  const auto s = fit::summarize(two_rows());
  EXPECT_NEAR(s.omega_min_rad_s, 2 * core::kPi, 1e-12);
  EXPECT_NEAR(s.omega_max_rad_s, 20 * core::kPi, 1e-12);
  EXPECT_EQ(s.storage_min_MPa, 2.0);
  EXPECT_EQ(s.storage_max_MPa, 3.0);
  EXPECT_EQ(s.loss_max_MPa, 1.0);
}
