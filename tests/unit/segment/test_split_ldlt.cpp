// The LDLᵀ in two halves at once (fitlib/src/segment/split_ldlt.hpp) on strip-shaped symmetric
// positive definite systems like the segment's (a long mesh of 8-equation elements): the separator
// splits the equations into two halves of at least 35 % each, the solution equals one LDLᵀ's to
// round-off (also where it is indefinite), refactorising new values on the same pattern works, the bytes do not depend on the
// thread count, and a system too small or without a balanced level set is left to one LDLᵀ.
#include <random>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include "../../../fitlib/src/segment/split_ldlt.hpp"

using namespace fitlib::segment::detail;

namespace {

// nx × ny nodes, two equations each, 4-node elements with random positive definite 8 × 8 blocks
// BᵀB + ½I (the tangent's pattern and definiteness).
Eigen::SparseMatrix<double> strip_system(int nx, int ny, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      int eq[8], k = 0;
      for (int node : {j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i})
        eq[k++] = 2 * node, eq[k++] = 2 * node + 1;
      Eigen::Matrix<double, 8, 8> B;
      for (int r = 0; r < 8; ++r)
        for (int c = 0; c < 8; ++c) B(r, c) = value(rng);
      const Eigen::Matrix<double, 8, 8> A = B.transpose() * B + 0.5 * Eigen::Matrix<double, 8, 8>::Identity();
      for (int r = 0; r < 8; ++r)
        for (int c = 0; c < 8; ++c) entries.emplace_back(eq[r], eq[c], A(r, c));
    }
  Eigen::SparseMatrix<double> K(2 * nx * ny, 2 * nx * ny);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = value(rng);
  return b;
}

}  // namespace

TEST(SplitLdlt, SolvesAStripAsOneLdltDoesOnTwoBalancedHalves) {
  WorkerPool team(2);
  for (unsigned seed : {1u, 2u, 3u}) {
    Eigen::SparseMatrix<double> K = strip_system(60, 5, seed);
    const int n = static_cast<int>(K.rows());
    SplitLdlt split;
    ASSERT_TRUE(split.analyze(K));
    EXPECT_EQ(split.half_size(0) + split.half_size(1) + split.separator_size(), n);
    EXPECT_LE(split.separator_size(), 2 * 5 * 2) << "a level set of a 5-node-high strip is one or two columns";
    for (int h = 0; h < 2; ++h) EXPECT_GE(split.half_size(h), SplitLdlt::kSmallestHalf * n - 1);
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> one;
    for (int refactorisation = 0; refactorisation < 2; ++refactorisation) {
      if (refactorisation) K = strip_system(60, 5, seed + 10);  // new values, the same pattern
      ASSERT_TRUE(split.factorize(K, team));
      one.compute(K);
      const Eigen::VectorXd b = random_vector(n, seed), x = split.solve(b, team), reference = one.solve(b);
      EXPECT_LT((x - reference).norm(), 1e-12 * reference.norm()) << "seed " << seed;
      EXPECT_LT((K * x - b).norm(), 1e-12 * b.norm());
    }
  }
}

TEST(SplitLdlt, SolvesAnIndefiniteStripAsOneLdltDoes) {
  // A tangent that is not definite (the plain pressure term at the load cycle's transitions): the
  // halves' LDLᵀ take negative pivots as one LDLᵀ does, the Schur complement is indefinite too.
  WorkerPool team(2);
  Eigen::SparseMatrix<double> K = strip_system(60, 5, 4);
  Eigen::SparseMatrix<double> shift(K.rows(), K.cols());
  shift.setIdentity();
  K -= 3.0 * shift;  // some eigenvalues below zero
  const int n = static_cast<int>(K.rows());
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(K)).eigenvalues();
  ASSERT_LT(eigenvalues[0], 0.0);
  ASSERT_GT(eigenvalues[n - 1], 0.0);
  SplitLdlt split;
  ASSERT_TRUE(split.analyze(K));
  ASSERT_TRUE(split.factorize(K, team));
  const Eigen::VectorXd b = random_vector(n, 5), x = split.solve(b, team);
  EXPECT_LT((K * x - b).norm(), 1e-10 * b.norm());
}

TEST(SplitLdlt, TheBytesDoNotDependOnTheThreadCount) {
  const Eigen::SparseMatrix<double> K = strip_system(40, 4, 7);
  const Eigen::VectorXd b = random_vector(static_cast<int>(K.rows()), 8);
  WorkerPool alone(1), team(2);
  SplitLdlt a, t;
  ASSERT_TRUE(a.analyze(K) && t.analyze(K));
  ASSERT_TRUE(a.factorize(K, alone) && t.factorize(K, team));
  const Eigen::VectorXd xa = a.solve(b, alone), xt = t.solve(b, team);
  for (int i = 0; i < b.size(); ++i) ASSERT_EQ(xa[i], xt[i]) << i;
}

TEST(SplitLdlt, SmallCompactOrDisconnectedSystemsAreLeftToOneLdlt) {
  SplitLdlt split;
  EXPECT_FALSE(split.analyze(strip_system(4, 4, 1)));  // 32 equations
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(80, 80);
  const Eigen::MatrixXd dense = B.transpose() * B + Eigen::MatrixXd::Identity(80, 80);
  EXPECT_FALSE(split.analyze(dense.sparseView()));  // every equation couples every other: one level
  Eigen::SparseMatrix<double> two(400, 400);  // two strips side by side, not coupled
  const Eigen::SparseMatrix<double> one = strip_system(20, 5, 1);
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < one.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(one, k); it; ++it)
      entries.emplace_back(it.row(), it.col(), it.value()), entries.emplace_back(it.row() + 200, it.col() + 200, it.value());
  two.setFromTriplets(entries.begin(), entries.end());
  EXPECT_FALSE(split.analyze(two));
  EXPECT_TRUE(split.analyze(strip_system(12, 12, 1)));  // a square splits along a diagonal level set
}
