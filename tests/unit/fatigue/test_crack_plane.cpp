#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/core/rng.hpp"
#include "fitlib/fatigue/crack_plane.hpp"

namespace fitlib::fatigue {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

TEST(CrackPlane, RotationByHand) {
  // θ = 30°: sin = 1/2, cos = √3/2; σ = s11/4 + 3 s22/4 − s12 √3/2, τ = (s22 − s11)√3/4 + s12/2.
  const PlaneStress s{1.0, 3.0, 0.5};
  const CrackPlaneStress c = crack_plane_stress(s, 30.0 * kDeg);
  EXPECT_NEAR(c.normal_MPa, 0.25 + 2.25 - 0.5 * std::sqrt(3.0) / 2.0, 1e-14);
  EXPECT_NEAR(c.shear_MPa, 2.0 * std::sqrt(3.0) / 4.0 + 0.25, 1e-14);
  // θ = 0: the radial crack opens under σ22 and shears under σ12.
  const CrackPlaneStress r = crack_plane_stress(s, 0.0);
  EXPECT_DOUBLE_EQ(r.normal_MPa, 3.0);
  EXPECT_DOUBLE_EQ(r.shear_MPa, 0.5);
  // θ = 90°: the longitudinal crack, normal radial (mode 2's plane): σ = s11, τ = −s12.
  const CrackPlaneStress l = crack_plane_stress(s, 90.0 * kDeg);
  EXPECT_NEAR(l.normal_MPa, 1.0, 1e-14);
  EXPECT_NEAR(std::abs(l.shear_MPa), 0.5, 1e-14);
}

TEST(CrackPlane, EffectiveStressOpenAndClosed) {
  EXPECT_DOUBLE_EQ(effective_stress_MPa({3.0, 4.0}), 5.0);   // open: √(σ² + τ²)
  EXPECT_DOUBLE_EQ(effective_stress_MPa({0.0, -4.0}), 4.0);  // σ = 0 belongs to the open branch
  EXPECT_DOUBLE_EQ(effective_stress_MPa({-3.0, -4.0}), 4.0);  // closed: |τ| only
  EXPECT_DOUBLE_EQ(separation_stress_MPa({-2.0, 7.0, 1.5}), 1.5);
  EXPECT_DOUBLE_EQ(separation_stress_MPa({2.0, 7.0, 1.5}), 2.5);
}

TEST(CrackPlane, UniaxialStatesByHand) {
  double angle = 1.0;
  // Longitudinal tension: worst at the radial direction, σ_e = σ22.
  EXPECT_NEAR(worst_radial_crack_stress_MPa({0.0, 10.0, 0.0}, 25.0 * kDeg, &angle), 10.0, 1e-12);
  EXPECT_NEAR(angle, 0.0, 1e-12);
  // Longitudinal compression closes every crack in the sweep: σ_e = |τ| = 10 sin θ cos θ,
  // largest at the sweep's ends.
  EXPECT_NEAR(worst_radial_crack_stress_MPa({0.0, -10.0, 0.0}, 25.0 * kDeg, &angle),
              10.0 * std::sin(25.0 * kDeg) * std::cos(25.0 * kDeg), 1e-12);
  EXPECT_NEAR(std::abs(angle), 25.0 * kDeg, 1e-12);
  // With ±45° the shear maximum 5 at 45° is reached.
  EXPECT_NEAR(worst_radial_crack_stress_MPa({0.0, -10.0, 0.0}, 45.0 * kDeg), 5.0, 1e-12);
  // No sweep: exactly the radial crack.
  EXPECT_NEAR(worst_radial_crack_stress_MPa({2.0, -1.0, 0.7}, 0.0), 0.7, 1e-14);
}

TEST(CrackPlane, SweepMatchesADenseGrid) {
  core::Rng rng(11);
  for (int k = 0; k < 300; ++k) {
    const PlaneStress s{rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-3, 3)};
    const double sweep = rng.uniform(0.0, 60.0) * kDeg;
    double grid = 0.0;
    for (int i = 0; i <= 40000; ++i) {
      const double th = -sweep + 2.0 * sweep * i / 40000.0;
      grid = std::max(grid, effective_stress_MPa(crack_plane_stress(s, th)));
    }
    const double exact = worst_radial_crack_stress_MPa(s, sweep);
    EXPECT_GE(exact, grid - 1e-12);
    EXPECT_NEAR(exact, grid, 1e-5 * (1.0 + grid)) << k;
  }
}

}  // namespace
}  // namespace fitlib::fatigue
