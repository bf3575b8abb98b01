// The covariance shared by the viscoelastic and hyperelastic fits (fit/scaled_spectrum.hpp): the rank
// test is made on the column-scaled Jacobian, so a parameter's unit does not decide whether it is
// identifiable, and the covariance is the unscaled pseudo-inverse's.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "../../../fitlib/src/fit/scaled_spectrum.hpp"

namespace fitlib::fit::detail {
namespace {

// A well-posed two-parameter Jacobian with one column in units 10¹² times smaller (D1 in 1/MPa beside
// a modulus in MPa, say): full rank, and the covariance equals s² (JᵀJ)⁻¹ computed directly.
TEST(ScaledSpectrum, AColumnInTinyUnitsIsStillIdentifiable) {
  Eigen::MatrixXd J(5, 2);
  J << 1.0, 2e-12, 2.0, 1e-12, 3.0, 5e-12, 4.0, 3e-12, 5.0, 1e-12;
  const Eigen::JacobiSVD<Eigen::MatrixXd> unscaled(J);
  ASSERT_LT(unscaled.singularValues()[1], 1e-10 * unscaled.singularValues()[0]);  // an unscaled test says deficient
  const ScaledSpectrum sp = scaled_spectrum(J);
  EXPECT_EQ(sp.rank, 2);
  const Eigen::MatrixXd cov = scaled_covariance(sp, 0.5), direct = 0.5 * (J.transpose() * J).inverse();
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) EXPECT_NEAR(cov(a, b), direct(a, b), 1e-10 * std::abs(direct(a, b))) << a << b;
}

// Two proportional columns (a parameter pair the data see only as a product or a sum) and a column
// without effect: rank 1 of 3, and the column without effect has zero variance.
TEST(ScaledSpectrum, DependentColumnsAndAColumnWithoutEffectLowerTheRank) {
  Eigen::MatrixXd J(4, 3);
  J << 1.0, 3.0, 0.0, 2.0, 6.0, 0.0, 3.0, 9.0, 0.0, 4.0, 12.0, 0.0;
  const ScaledSpectrum sp = scaled_spectrum(J);
  EXPECT_EQ(sp.rank, 1);
  EXPECT_EQ(scaled_covariance(sp, 1.0)(2, 2), 0.0);
}

}  // namespace
}  // namespace fitlib::fit::detail
