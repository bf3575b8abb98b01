// Bernstein basis against Report V Eq 5.2 and its derivatives against finite differences.
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/surface/bernstein.hpp"

using namespace fitlib::surface;

TEST(Bernstein, DegreeTwoMatchesEquation52) {
  for (double t : {0.0, 0.1, 0.37, 0.5, 0.9, 1.0}) {
    double b[3];
    bernstein(2, t, b);
    EXPECT_NEAR(b[0], (1 - t) * (1 - t), 1e-15);  // 2!/(2!0!) t^0 (1-t)^2
    EXPECT_NEAR(b[1], 2 * t * (1 - t), 1e-15);
    EXPECT_NEAR(b[2], t * t, 1e-15);
  }
}

TEST(Bernstein, PartitionOfUnityAndExactEndValues) {
  for (int d = 0; d <= 6; ++d) {
    double b[7];
    for (double t : {0.0, 0.2, 0.55, 1.0}) {
      bernstein(d, t, b);
      double sum = 0;
      for (int i = 0; i <= d; ++i) sum += b[i];
      EXPECT_NEAR(sum, 1.0, 1e-14) << "Eq 5.11: the blending functions sum to one";
    }
    bernstein(d, 1.0, b);
    for (int i = 0; i < d; ++i) EXPECT_EQ(b[i], 0.0) << "B_i(1) = 0 exactly for i < d";
    EXPECT_EQ(b[d], 1.0);
  }
}

TEST(Bernstein, DerivativeMatchesCentralDifference) {
  const double h = 1e-6;
  for (int d = 1; d <= 6; ++d)
    for (double t : {0.1, 0.5, 0.83}) {
      double b[7], db[7], bp[7], bm[7];
      bernstein_with_derivative(d, t, b, db);
      bernstein(d, t + h, bp);
      bernstein(d, t - h, bm);
      double plain[7];
      bernstein(d, t, plain);
      for (int i = 0; i <= d; ++i) {
        EXPECT_NEAR(db[i], (bp[i] - bm[i]) / (2 * h), 1e-7);
        EXPECT_NEAR(b[i], plain[i], 1e-15);
      }
    }
}

TEST(Bernstein, SecondDifferenceIsReportVsBsecond) {
  // B''_{i,2} = [2, -4, 2] (Report V §5.3), proportional to the forward difference [1, -2, 1].
  EXPECT_EQ(forward_difference_coefficient(2, 0), 1.0);
  EXPECT_EQ(forward_difference_coefficient(2, 1), -2.0);
  EXPECT_EQ(forward_difference_coefficient(2, 2), 1.0);
  EXPECT_EQ(forward_difference_coefficient(3, 1), 3.0);
  EXPECT_EQ(forward_difference_coefficient(3, 0), -1.0);
}
