// Parametric neutral-layer curve (belt-mechanics.md §3): exact circle and straight line.
#include <cmath>

#include <gtest/gtest.h>

#include "fitlib/segment/curve.hpp"

using fitlib::segment::NeutralCurve;

TEST(NeutralCurve, UniformCurvatureIsTheExactCircleThroughTheOrigin) {
  const double K = 1.0 / 40.0;
  const NeutralCurve c = NeutralCurve::uniform(K, 0.0, 30.0, 6);
  for (double s : {-29.0, -12.5, -0.3, 0.0, 4.0, 17.0, 30.0, 45.0}) {
    const auto p = c.at(s);
    EXPECT_NEAR(p.x_mm, 40.0 * std::sin(s * K), 1e-12);          // centre (0, −40)
    EXPECT_NEAR(p.y_mm, 40.0 * std::cos(s * K) - 40.0, 1e-12);
    EXPECT_NEAR(p.phi_rad, s * K, 1e-14);
  }
}

TEST(NeutralCurve, InverseMapGivesPathPositionAndDepthOnACircle) {
  const double K = -1.0 / 25.0;  // bent the other way: centre above at (0, 25)
  const NeutralCurve c = NeutralCurve::uniform(K, 0.01, 20.0, 5);
  for (double s : {-18.0, -3.0, 0.5, 7.0, 19.0})
    for (double h : {0.0, 1.5, 4.0}) {
      const double phi = K * s;
      // h below the curve = away from the centre for K < 0
      const double x = (25.0 + h) * std::sin(-phi), y = 25.0 - (25.0 + h) * std::cos(phi);
      const auto q = c.coordinates(x, y);
      EXPECT_NEAR(q.s_mm, s, 1e-10);
      EXPECT_NEAR(q.h_mm, h, 1e-10);
      EXPECT_NEAR(q.phi_rad, phi, 1e-12);
    }
}

TEST(NeutralCurve, ZeroCurvatureIsAStraightLineAndStrainStretchesPathPositions) {
  const NeutralCurve c = NeutralCurve::uniform(0.0, 0.02, 25.0, 4);
  const auto p = c.at(-10.0);
  EXPECT_NEAR(p.x_mm, -10.0, 1e-14);
  EXPECT_NEAR(p.y_mm, 0.0, 1e-14);
  EXPECT_NEAR(c.s_from_unstrained(10.0), 10.2, 1e-12);
  EXPECT_NEAR(c.unstrained_from_s(-10.2), -10.0, 1e-12);
  const auto q = c.coordinates(3.0, -2.0);
  EXPECT_NEAR(q.s_mm, 3.0, 1e-14);
  EXPECT_NEAR(q.h_mm, 2.0, 1e-14);
}

TEST(NeutralCurve, Corrected519InvertsTheUnstrainedLengthForLinearlyVaryingStrain) {
  // ε from 0 at the origin to 0.1 at the end of the first interval, then 0.05, …
  const std::vector<double> K{0.01, 0.02, 0.0}, eps{0.0, 0.1, 0.05, 0.05};
  const NeutralCurve c(10.0, K, eps, K, eps);
  // Independent: ds_org/ds = a0 + (a1 − a0) s/Δs on the first interval, closed-form integral.
  const double a0 = 1.0, a1 = 1.0 / 1.1, s = 6.0;
  const double s_org = a0 * s + (a1 - a0) * s * s / 20.0;
  EXPECT_NEAR(c.unstrained_from_s(s), s_org, 1e-13);
  EXPECT_NEAR(c.s_from_unstrained(s_org), s, 1e-12);
  for (double t : {-27.0, -10.0, 3.0, 14.0, 29.0, 40.0})
    EXPECT_NEAR(c.s_from_unstrained(c.unstrained_from_s(t)), t, 1e-11) << t;
}
