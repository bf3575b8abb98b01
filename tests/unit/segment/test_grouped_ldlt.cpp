// The segment's LDLᵀ ordering (fitlib/src/segment/grouped_ldlt.hpp) behind Eigen's SimplicialLDLT:
// the order a permutation that keeps each node's equations together, the solution of grid-shaped
// symmetric systems (definite and indefinite) against a dense LDLᵀ, a refactorisation with new
// values on the same pattern, and a factor no fuller than Eigen's own AMD gives.
#include <algorithm>
#include <cstdio>
#include <random>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include "../../../fitlib/src/segment/grouped_ldlt.hpp"

using namespace fitlib::segment::detail;

namespace {

// A 4-node-element grid of nx × ny nodes, two equations per node except the bottom row's nodes,
// whose vertical equation is prescribed (a one-equation group); random symmetric values with a
// dominant diagonal (the tangent's pattern: every pair of equations of an element couples).
Eigen::SparseMatrix<double> grid_system(int nx, int ny, unsigned seed, std::vector<int>& node_of_equation) {
  std::vector<std::vector<int>> eq(nx * ny);
  node_of_equation.clear();
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      for (int c = 0; c < (j == 0 ? 1 : 2); ++c) {
        eq[j * nx + i].push_back(static_cast<int>(node_of_equation.size()));
        node_of_equation.push_back(j * nx + i);
      }
  const int n = static_cast<int>(node_of_equation.size());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      std::vector<int> e;
      for (int node : {j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i})
        e.insert(e.end(), eq[node].begin(), eq[node].end());
      for (int r : e)
        for (int c : e) dense(r, c) += r == c ? 10.0 : value(rng);
    }
  const Eigen::MatrixXd symmetric = 0.5 * (dense + dense.transpose());
  return symmetric.sparseView();
}

// The order as Eigen's ordering concept (SimplicialLDLT's third template argument): perm maps a
// position of the elimination order to its equation, as Eigen's AMDOrdering does.
struct GroupedAmdOrdering {
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  template <typename MatrixType>
  void operator()(const MatrixType& A, PermutationType& perm) {
    const std::vector<int> order = grouped_amd_order(Eigen::SparseMatrix<double>(A));
    perm.resize(static_cast<int>(order.size()));
    for (std::size_t p = 0; p < order.size(); ++p) perm.indices()(static_cast<int>(p)) = order[p];
  }
};

template <typename Ordering>
using Ldlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Ordering>;

}  // namespace

TEST(SegmentGroupedLdlt, SolvesAGridSystemAsADenseLdltDoesWithNoMoreFillThanEigensAmd) {
  std::vector<int> node_of;
  const Eigen::SparseMatrix<double> K = grid_system(9, 5, 7, node_of);
  Ldlt<GroupedAmdOrdering> grouped(K);
  ASSERT_EQ(grouped.info(), Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), -1.0, 2.0);
  const Eigen::VectorXd expected = Eigen::MatrixXd(K).ldlt().solve(b);
  EXPECT_LT((grouped.solve(b) - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  // The permutation is the order (not its inverse): the factor is no fuller than with Eigen's AMD
  // on the equations, and sparser than in the natural (row-by-row) order.
  const Ldlt<Eigen::AMDOrdering<int>> amd(K);
  const Ldlt<Eigen::NaturalOrdering<int>> natural(K);
  const auto fill = [](const auto& ldlt) { return Eigen::SparseMatrix<double>(ldlt.matrixL()).nonZeros(); };
  std::printf("factor nonzeros: grouped AMD %ld, Eigen AMD %ld, natural %ld\n", static_cast<long>(fill(grouped)),
              static_cast<long>(fill(amd)), static_cast<long>(fill(natural)));
  EXPECT_LE(fill(grouped), fill(amd));
  EXPECT_LT(fill(grouped), fill(natural));
  const std::vector<int> order = grouped_amd_order(K);
  for (int p = 0; p < K.rows(); ++p) EXPECT_EQ(grouped.permutationPinv().indices()(p), order[p]);
}

TEST(SegmentGroupedLdlt, OrderIsAPermutationKeepingEachNodesEquationsTogether) {
  std::vector<int> node_of;
  const Eigen::SparseMatrix<double> K = grid_system(9, 5, 7, node_of);
  const std::vector<int> order = grouped_amd_order(K);
  ASSERT_EQ(order.size(), static_cast<std::size_t>(K.rows()));
  std::vector<int> seen(order.size(), 0);
  for (int e : order) ++seen.at(e);
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), K.rows());
  for (std::size_t p = 0; p + 1 < order.size(); ++p)  // a node's two equations: consecutive, in order
    if (node_of[order[p]] == node_of[order[p + 1]]) {
      EXPECT_EQ(order[p + 1], order[p] + 1);
    }
  int pairs = 0;
  for (std::size_t p = 0; p + 1 < order.size(); ++p) pairs += node_of[order[p]] == node_of[order[p + 1]];
  EXPECT_EQ(pairs, 9 * 4);  // every node above the bottom row
}

TEST(SegmentGroupedLdlt, RefactorisesNewValuesOnTheAnalysedPattern) {
  std::vector<int> node_of;
  const Eigen::SparseMatrix<double> K1 = grid_system(6, 4, 1, node_of), K2 = grid_system(6, 4, 2, node_of);
  Ldlt<GroupedAmdOrdering> ldlt;
  ldlt.analyzePattern(K1);
  ldlt.factorize(K1);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  ldlt.factorize(K2);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(K2.rows());
  EXPECT_LT((K2 * ldlt.solve(b) - b).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SegmentGroupedLdlt, IndefiniteSystemAsADenseLdlt) {
  // No pivoting, as the tangent's LDLᵀ: an indefinite matrix (negative diagonal on half the
  // equations) is solved as a dense LDLᵀ solves it.
  std::vector<int> node_of;
  Eigen::SparseMatrix<double> K = grid_system(7, 4, 3, node_of);
  for (int j = 0; j < K.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it)
      if (it.row() == it.col() && j % 2 == 1) it.valueRef() = -it.value();
  const Ldlt<GroupedAmdOrdering> ldlt(K);
  ASSERT_EQ(ldlt.info(), Eigen::Success);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, -3.0);
  const Eigen::VectorXd expected = Eigen::MatrixXd(K).ldlt().solve(b);
  EXPECT_LT((ldlt.solve(b) - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
  EXPECT_LT((K * ldlt.solve(b) - b).cwiseAbs().maxCoeff(), 1e-11);
}
