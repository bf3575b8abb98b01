// The critical mode of a tangent (fitlib/src/segment/critical_mode.hpp; SteppingOptions::branch_switch):
// the eigenpair of the symmetric part nearest zero against the closed form of a shifted second
// difference matrix, whose eigenvalues are 2 − 2cos(kπ/(n+1)) − σ and eigenvectors sin(ikπ/(n+1)).
#include <cmath>

#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include "../../../fitlib/src/segment/critical_mode.hpp"

using fitlib::segment::detail::critical_mode;

namespace {

// The n × n second difference matrix shifted by −σ, plus an antisymmetric part of size `skew`
// (the critical mode reads only the symmetric part).
Eigen::SparseMatrix<double> shifted_laplacian(int n, double sigma, double skew) {
  Eigen::SparseMatrix<double> K(n, n);
  for (int i = 0; i < n; ++i) {
    K.insert(i, i) = 2.0 - sigma;
    if (i + 1 < n) K.insert(i, i + 1) = -1.0 + skew, K.insert(i + 1, i) = -1.0 - skew;
  }
  K.makeCompressed();
  return K;
}

double eigenvalue(int n, int k, double sigma) { return 2.0 - 2.0 * std::cos(k * M_PI / (n + 1)) - sigma; }

}  // namespace

// σ between the first and second eigenvalues: the lowest is negative (a bifurcation passed), the
// nearest to zero; its vector is the first sine.
TEST(CriticalMode, FindsTheNegativeEigenvalueNearestZeroAndItsSineMode) {
  const int n = 200;
  const double sigma = eigenvalue(n, 1, 0.0) + 0.3 * (eigenvalue(n, 2, 0.0) - eigenvalue(n, 1, 0.0));
  const auto c = critical_mode(shifted_laplacian(n, sigma, 0.4));
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.eigenvalue, eigenvalue(n, 1, sigma), 1e-9 * std::abs(eigenvalue(n, 1, sigma)) + 1e-12);
  EXPECT_LT(c.eigenvalue, 0.0);
  EXPECT_EQ(c.negative, 1);
  Eigen::VectorXd sine(n);
  for (int i = 0; i < n; ++i) sine(i) = std::sin((i + 1) * M_PI / (n + 1));
  EXPECT_NEAR(std::abs(c.mode.dot(sine.normalized())), 1.0, 1e-8);
}

// Past the second eigenvalue's zero the nearest to zero is the second (one sign change): inverse
// iteration picks the eigenvalue of smallest magnitude, not the algebraically lowest.
TEST(CriticalMode, PicksTheEigenvalueOfSmallestMagnitude) {
  const int n = 50;
  const double sigma = eigenvalue(n, 2, 0.0) + 1e-3;
  const auto c = critical_mode(shifted_laplacian(n, sigma, 0.0));
  ASSERT_TRUE(c.found);
  EXPECT_NEAR(c.eigenvalue, -1e-3, 1e-10);
  EXPECT_EQ(c.negative, 2);
}
