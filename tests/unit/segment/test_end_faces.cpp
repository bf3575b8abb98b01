// The long-belt section behind the sheared end faces (segment/end_faces.hpp; docs/segment.md
// "End faces"): Jourawski's shear and the warping against closed forms, the small-strain moduli of
// the isotropic law, and the shear-lag smoothing.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "fitlib/segment/end_faces.hpp"

namespace fitlib::segment {
namespace {

// The rubber area per pitch below the cord line, by midpoints of the profile (independent of the
// section's own column sums).
double rubber_depth_mm(const CogSection& s) {
  const int n = 90000;
  double area = 0.0;
  for (int i = 0; i < n; ++i) area -= s.bottom_y_mm(-0.5 * s.cog_pitch_mm + (i + 0.5) * s.cog_pitch_mm / n);
  return area / n;
}

}  // namespace

TEST(SegmentEndFaces, SmallStrainModuliOfTheIsotropicLaw) {
  const auto law = make_elastic(ElasticLaw::hencky, 20.0, 0.49);
  EXPECT_NEAR(shear_modulus_MPa(*law), 20.0 / (2.0 * 1.49), 1e-9);
  EXPECT_NEAR(axial_modulus_MPa(*law), 20.0 / (1.0 - 0.49 * 0.49), 1e-9);  // plane strain, σ_yy = 0
}

// One material (E 20 MPa, ν 0.49), depths within the full-width layer above the land (h ≤ 4.1 mm):
// σ12(h) = −b (A − h) − ε' E' (D − h) + K' E' (D² − h²)/2, A the rubber depth per pitch, D the land's
// depth; the warping u(h) = −∫_0^h σ12/G dh'.
TEST(SegmentEndFaces, ShearAndWarpingOfTheLayerFollowJourawski) {
  const CogSection s;
  const auto law = make_elastic(ElasticLaw::hencky, 20.0, 0.49);
  const LongBeltSection section(s, 13.5, {law.get(), law.get()});
  const double A = rubber_depth_mm(s), D = -s.land_y_mm(), E = 20.0 / (1.0 - 0.49 * 0.49), G = 20.0 / 2.98;
  const double b = 0.1, de = 2e-4, dK = -3e-4;
  for (double h : {0.0, 0.25, 1.0, 2.5, 4.0}) {
    const double tau = -b * (A - h) - de * E * (D - h) + dK * E * (D * D - h * h) / 2.0;
    EXPECT_NEAR(section.shear_MPa({b, 0.0, 0.0}, h), -b * (A - h), 2e-3 * b * A) << h;
    EXPECT_NEAR(section.shear_MPa({b, de, dK}, h), tau, 2e-3 * b * A) << h;
    const double u = (b * (A * h - h * h / 2.0) + de * E * (D * h - h * h / 2.0) - dK * E * (D * D * h - h * h * h / 3.0) / 2.0) / G;
    EXPECT_NEAR(section.warping_mm({b, de, dK}, h), u, 2e-3 * b * A * D / G) << h;
  }
  // Below the land only the friction of the cog below is left; nothing at the tip.
  EXPECT_NEAR(section.shear_MPa({0.0, de, dK}, 5.0), 0.0, 1e-12);
  EXPECT_NEAR(section.shear_MPa({b, 0.0, 0.0}, s.height_mm), 0.0, 1e-12);
  EXPECT_GT(section.shear_lag_mm(), 3.0);  // sqrt(EA/k): several mm for a 6.6 mm deep belt
  EXPECT_LT(section.shear_lag_mm(), 15.0);
}

// The smoothing is a convolution with e^(−|s|/ℓ)/(2ℓ): a constant is kept, a unit load at one
// sample spreads as that kernel with its total kept (periodic).
TEST(SegmentEndFaces, ShearLagSmoothingIsTheExponentialKernel) {
  const double ds = 0.25, lag = 7.0;
  const std::vector<double> constant(400, 3.0);
  for (double v : shear_lag_smoothed(constant, ds, lag)) EXPECT_NEAR(v, 3.0, 1e-12);
  std::vector<double> spike(4000, 0.0);
  spike[1000] = 1.0 / ds;  // a unit load
  const std::vector<double> out = shear_lag_smoothed(spike, ds, lag);
  EXPECT_NEAR(std::accumulate(out.begin(), out.end(), 0.0) * ds, 1.0, 1e-9);
  for (int d : {0, 8, 40, 120})
    EXPECT_NEAR(out[1000 + d] / out[1000], std::exp(-d * ds / lag), 1e-9) << d;
  EXPECT_NEAR(out[1000], 1.0 / (2.0 * lag), 0.02 / (2.0 * lag));  // the continuous kernel's peak
}

}  // namespace fitlib::segment
