// Lawson–Hanson NNLS against exact solutions and a brute-force enumeration of active sets.
#include <gtest/gtest.h>

#include <Eigen/QR>

#include "fitlib/core/rng.hpp"
#include "fitlib/fit/nnls.hpp"

using fitlib::fit::nnls;

namespace {

Eigen::MatrixXd random_matrix(int rows, int cols, fitlib::core::Rng& rng) {
  Eigen::MatrixXd a(rows, cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) a(i, j) = rng.normal();
  return a;
}

}  // namespace

TEST(Nnls, RecoversAPositiveSolutionExactly) {
  fitlib::core::Rng rng(7);
  const Eigen::MatrixXd a = random_matrix(40, 8, rng);
  Eigen::VectorXd x_true(8);
  for (int j = 0; j < 8; ++j) x_true[j] = 0.5 + j;
  const auto r = nnls(a, a * x_true);
  ASSERT_TRUE(r.converged);
  EXPECT_LT((r.x - x_true).norm(), 1e-10 * x_true.norm());
  EXPECT_LT(r.residual_norm, 1e-9);
}

// For small n, the NNLS optimum is the best of the unconstrained solutions on every subset of
// columns that comes out non-negative.
TEST(Nnls, MatchesBruteForceOverAllActiveSets) {
  fitlib::core::Rng rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 5;
    const Eigen::MatrixXd a = random_matrix(12, n, rng);
    Eigen::VectorXd b(12);
    for (int i = 0; i < 12; ++i) b[i] = rng.normal();
    double best = b.norm();
    for (int mask = 1; mask < (1 << n); ++mask) {
      std::vector<int> cols;
      for (int j = 0; j < n; ++j)
        if (mask & (1 << j)) cols.push_back(j);
      Eigen::MatrixXd sub(12, static_cast<int>(cols.size()));
      for (std::size_t k = 0; k < cols.size(); ++k) sub.col(k) = a.col(cols[k]);
      const Eigen::VectorXd x = sub.colPivHouseholderQr().solve(b);
      if ((x.array() >= 0.0).all()) best = std::min(best, (sub * x - b).norm());
    }
    const auto r = nnls(a, b);
    ASSERT_TRUE(r.converged) << "trial " << trial;
    EXPECT_TRUE((r.x.array() >= 0.0).all());
    EXPECT_NEAR(r.residual_norm, best, 1e-10 * (1.0 + best)) << "trial " << trial;
  }
}

// A Prony design matrix over 60 closely spaced time constants is numerically rank deficient;
// the solver must still return a non-negative, finite, KKT-checked answer.
TEST(Nnls, IllConditionedPronyDesignStaysFiniteAndNonNegative) {
  const int rows = 200, cols = 60;
  Eigen::MatrixXd a(2 * rows, cols);
  Eigen::VectorXd b(2 * rows);
  for (int i = 0; i < rows; ++i) {
    const double omega = std::pow(10.0, -3.0 + 6.0 * i / (rows - 1));
    double storage = 1.0, loss = 0.0;
    for (int j = 0; j < cols; ++j) {
      const double tau = std::pow(10.0, -3.0 + 6.0 * j / (cols - 1));
      const double wt = omega * tau;
      a(i, j) = wt * wt / (1.0 + wt * wt);
      a(rows + i, j) = wt / (1.0 + wt * wt);
      if (j % 7 == 0) {
        storage += a(i, j);
        loss += a(rows + i, j);
      }
    }
    b[i] = storage - 1.0;
    b[rows + i] = loss;
  }
  const auto r = nnls(a, b);
  EXPECT_TRUE(r.x.allFinite());
  EXPECT_TRUE((r.x.array() >= 0.0).all());
  EXPECT_LT(r.residual_norm, 1e-6 * b.norm());
}

TEST(Nnls, AllNegativeTargetGivesZero) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(3, 3);
  const auto r = nnls(a, Eigen::Vector3d(-1.0, -2.0, -3.0));
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.x.norm(), 0.0);
}
