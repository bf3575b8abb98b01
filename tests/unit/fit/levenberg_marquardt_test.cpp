// Levenberg–Marquardt on the normal equations (fit/levenberg_marquardt.cpp, the --terms N polish):
// on known-truth Prony data it reaches Ceres's cost, its gradient vanishes there, it stops on an
// active bound as Ceres does, and fit() with it gives Ceres's card figures.
#include <gtest/gtest.h>

#include <Eigen/QR>

#include <cmath>
#include <cstdio>
#include <vector>

#include "../../../fitlib/src/fit/backends.hpp"
#include "../card/known_truth.hpp"
#include "fit_testing.hpp"
#include "fitlib/fit/problem.hpp"

namespace fitlib {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Case {
  data::DynamicTestTable table;
  model::ModelPtr model;
  std::vector<double> truth;
};

// 10–12 terms one per decade, 1 % noise, 20 points per decade (the FixedTerms tests' data).
Case known_truth(std::uint64_t seed) {
  const double decades = 8.0 + (seed % 3);
  const int terms = static_cast<int>(decades) + 2;
  const auto t = card::testing::smooth_truth(terms, 1e-5 / (2.0 * M_PI), seed);
  const auto f = fit::testing::log_frequencies(1e-4, 1e-4 * std::pow(10.0, decades), 20 * static_cast<int>(decades) + 1);
  return {fit::testing::synthetic_table(*t.model, t.p, f, 0.01, 100 + seed), t.model, t.p};
}

// The truth's moduli × `moduli_factor`, its times moved by up to ±`decades` (a start where the
// descent's basin is the truth's, as the merged NNLS start of --terms N is; or a far one).
std::vector<double> moved(const Case& c, double moduli_factor, double decades, std::uint64_t seed) {
  std::vector<double> p = c.truth;
  const int terms = (static_cast<int>(p.size()) - 1) / 2;
  for (int k = 1; k <= terms; ++k) {
    p[k] *= moduli_factor;
    p[terms + k] *= std::pow(10.0, decades * std::sin(1.7 * k + seed));
  }
  return p;
}

// The bench's data (bench_prony fixed): one term per decade over 14 decades, moduli 0.5–1.5 MPa,
// 200 points from 1e-6 to 1e8 Hz, 1 % noise.
Case bench_case(int terms, std::uint64_t seed) {
  const auto m = fit::testing::prony(terms);
  std::vector<double> truth{1.0};
  for (int i = 0; i < terms; ++i) truth.push_back(0.5 + std::fmod(0.37 * i, 1.0));
  for (double tau : fit::testing::log_frequencies(2e-8, 1e5, terms)) truth.push_back(tau);
  return {fit::testing::synthetic_table(*m, truth, fit::testing::log_frequencies(1e-6, 1e8, 200), 0.01, seed), m, truth};
}

// The largest component of the cost's gradient in fitted coordinates (ln p of the Prony parameters).
double gradient_norm(const fit::Problem& p) {
  const int m = p.num_residuals(), nf = p.num_free();
  RowMatrix j(m, nf);
  Eigen::VectorXd r(m);
  EXPECT_TRUE(p.evaluate(p.natural(), r.data(), j.data()));
  return (j.transpose() * r).cwiseAbs().maxCoeff();
}

fit::FitOptions tight() {
  fit::FitOptions o;
  o.tolerance = 1e-12;
  return o;
}

// From a start in the truth's basin: Ceres's cost to 1e-8 relative, the gradient ~0.
TEST(LevenbergMarquardt, ReachesCeresCostOnKnownTruthDataWithAVanishingGradient) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Case c = known_truth(seed);
    const std::vector<double> start = moved(c, 1.2, 0.05, seed);
    fit::Problem ceres(c.model, c.table, tight(), start), lm(c.model, c.table, tight(), start);
    const double start_cost = ceres.cost(ceres.natural()), start_gradient = gradient_norm(ceres);
    const auto by_ceres = fit::detail::run_ceres(ceres, 500);
    const auto by_lm = fit::detail::run_levenberg_marquardt(lm, 500);
    const double cost_ceres = ceres.cost(ceres.natural()), cost_lm = lm.cost(lm.natural());
    std::printf("seed %d: start cost %.6g, gradient %.2e; ceres %.12g (%d iterations, gradient %.2e), lm %.12g (%d "
                "iterations, gradient %.2e)\n",
                int(seed), start_cost, start_gradient, cost_ceres, by_ceres.iterations, gradient_norm(ceres), cost_lm,
                by_lm.iterations, gradient_norm(lm));
    ASSERT_TRUE(by_lm.usable);
    EXPECT_TRUE(by_lm.converged) << by_lm.note;
    EXPECT_LT(cost_lm, 0.01 * start_cost);
    EXPECT_NEAR(cost_lm, cost_ceres, 1e-8 * cost_ceres) << "seed " << seed;
    EXPECT_LT(gradient_norm(lm), 1e-6 * start_gradient) << "seed " << seed;
  }
}

// From a far start (moduli × 1.5, times moved by up to ±0.3 decade) the two descents may end in
// different minima: the normal equations' is a stationary point no more than 1 % above Ceres's.
TEST(LevenbergMarquardt, FromAFarStartEndsNoWorseThanCeresByMoreThanOnePercent) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Case c = known_truth(seed);
    const std::vector<double> start = moved(c, 1.5, 0.3, seed);
    fit::Problem ceres(c.model, c.table, tight(), start), lm(c.model, c.table, tight(), start);
    fit::detail::run_ceres(ceres, 500);
    const auto by_lm = fit::detail::run_levenberg_marquardt(lm, 500);
    const double cost_ceres = ceres.cost(ceres.natural()), cost_lm = lm.cost(lm.natural());
    std::printf("seed %d, far start: ceres %.12g, lm %.12g (%d iterations)\n", int(seed), cost_ceres, cost_lm,
                by_lm.iterations);
    EXPECT_TRUE(by_lm.converged) << by_lm.note;
    EXPECT_LE(cost_lm, 1.01 * cost_ceres) << "seed " << seed;
  }
}

// The bench's data, one time constant held above its optimum by a bound: the descent ends on the
// bound, at a stationary point of the other parameters, no higher than Ceres's (which ends above it
// here: 0.0228 against 0.0172).
TEST(LevenbergMarquardt, StopsOnAnActiveBoundNoHigherThanCeres) {
  const Case c = bench_case(15, 1);
  const std::vector<double> start = moved(c, 1.2, 0.05, 1);
  fit::Problem ceres(c.model, c.table, tight(), start), lm(c.model, c.table, tight(), start);
  const int held = 15 + 8;  // τ_8
  const double bound = 3.0 * c.truth[held];
  for (fit::Problem* p : {&ceres, &lm}) p->restrict_bounds(held, bound, HUGE_VAL);
  const double start_gradient = gradient_norm(lm);
  fit::detail::run_ceres(ceres, 500);
  const auto out = fit::detail::run_levenberg_marquardt(lm, 500);
  EXPECT_TRUE(out.converged) << out.note;
  EXPECT_DOUBLE_EQ(lm.natural()[held], bound);
  EXPECT_DOUBLE_EQ(ceres.natural()[held], bound);
  EXPECT_LE(lm.cost(lm.natural()), (1.0 + 1e-8) * ceres.cost(ceres.natural()));
  const int m = lm.num_residuals(), nf = lm.num_free();
  RowMatrix j(m, nf);
  Eigen::VectorXd r(m);
  ASSERT_TRUE(lm.evaluate(lm.natural(), r.data(), j.data()));
  Eigen::VectorXd g = j.transpose() * r;
  EXPECT_GT(g[held], 0.0);  // the cost would fall below the bound
  g[held] = 0.0;
  std::printf("on the bound: ceres %.12g, lm %.12g, gradient of the others %.2e\n", ceres.cost(ceres.natural()),
              lm.cost(lm.natural()), g.cwiseAbs().maxCoeff());
  EXPECT_LT(g.cwiseAbs().maxCoeff(), 1e-6 * start_gradient);
}

// The bench's data: fit() with the normal-equation descent (what --terms N polishes with) gives
// Ceres's figures from a start in the truth's basin, and says which descent ran.
TEST(LevenbergMarquardt, FitWithItGivesCeresFigures) {
  for (int terms : {10, 15}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      const Case c = bench_case(terms, seed);
      const std::vector<double> start = moved(c, 1.2, 0.05, seed);
      fit::FitOptions o;
      o.tolerance = 1e-12;
      const fit::FitResult by_ceres = fit::fit(c.model, c.table, o, &start);
      o.descent = fit::LocalDescent::normal_equations;
      const fit::FitResult by_lm = fit::fit(c.model, c.table, o, &start);
      std::printf("N %d, seed %d: fit() cost ceres %.12g, lm %.12g\n", terms, int(seed), by_ceres.metrics.cost,
                  by_lm.metrics.cost);
      EXPECT_EQ(by_lm.backend_used, "nnls+lm");
      EXPECT_NEAR(by_lm.metrics.cost, by_ceres.metrics.cost, 1e-8 * by_ceres.metrics.cost) << "seed " << seed;
      EXPECT_NEAR(by_lm.metrics.rms_log10_storage, by_ceres.metrics.rms_log10_storage, 1e-7);
      EXPECT_NEAR(by_lm.metrics.rms_log10_loss, by_ceres.metrics.rms_log10_loss, 1e-7);
      EXPECT_EQ(by_lm.metrics.rank, by_ceres.metrics.rank);
    }
  }
}

}  // namespace
}  // namespace fitlib
