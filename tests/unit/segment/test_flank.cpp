// The deformation-limited flank contact (segment/flank.hpp; docs/segment.md "Flank foundation"): the
// foundation's force and tangent at a point against central differences on a curved, strained cord
// curve; a block moved uniformly deeper carries k Δh V; a layer on the foundation under a uniform
// radial load against the closed form of a Winkler-supported bar, with Newton's quadratic rate.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "fitlib/segment/curve.hpp"
#include "fitlib/segment/elastic.hpp"
#include "fitlib/segment/flank.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/solver.hpp"
#include "strip.hpp"

using namespace fitlib::segment;

namespace {

constexpr double kHeight_mm = test::kStripHeight_mm;
using test::strip;

// The strip's foundation on a straight cord line that stays put, k everywhere.
StaticProblem::FollowingForce straight_foundation(const Mesh& m, double k) {
  std::vector<double> path_x;
  for (const Eigen::Vector2d& X : m.X) path_x.push_back(X.x());
  const NeutralCurve line = NeutralCurve::uniform(0.0, 0.0, 1.5 * m.half_length_mm);
  return flank_foundation(m, path_x, Integration::reduced, line, [line](double) { return line; },
                          [k, &m](double, std::vector<double>& per_element) { per_element.assign(m.element_count(), k); });
}

}  // namespace

TEST(SegmentFlank, FoundationForceAndTangentMatchCentralDifferences) {
  // A cord curve with arcs of both signs, a straight interval and a strain that varies along it.
  const std::vector<double> K_pos{0.02, 0.035, 0.0, -0.01, 0.025}, eps_pos{0.01, 0.012, 0.02, 0.015, 0.0, 0.005};
  const std::vector<double> K_neg{0.02, 0.0, 0.03, 0.04, -0.02}, eps_neg{0.01, 0.008, 0.0, 0.02, 0.01, 0.01};
  const NeutralCurve curve(3.0, K_pos, eps_pos, K_neg, eps_neg);
  const CurveStarts starts = curve.starts();
  const double k = 0.05, h = 1e-6;
  int points = 0;
  for (double s : {-12.5, -7.1, -4.4, -0.8, 0.6, 2.2, 5.0, 7.7, 10.9, 13.0})
    for (double depth : {0.3, 2.5, 6.2}) {
      const CurvePoint c = curve.at(s);
      const Eigen::Vector2d n(std::sin(c.phi_rad), std::cos(c.phi_rad));
      const Eigen::Vector2d x = Eigen::Vector2d(c.x_mm, c.y_mm) - depth * n;
      const double reference_depth = depth - 0.07;  // moved 0.07 mm deeper since the reference
      // The hinted map (from a hint 0.4 mm off) is the full inverse map.
      const CurveCoordinates full = curve.coordinates(x.x(), x.y()), at = curve.coordinates(x.x(), x.y(), starts, s + 0.4);
      EXPECT_NEAR(at.s_mm, full.s_mm, 1e-12);
      EXPECT_NEAR(at.h_mm, full.h_mm, 1e-12);
      EXPECT_NEAR(at.phi_rad, full.phi_rad, 1e-14);
      EXPECT_EQ(at.K_1_mm, full.K_1_mm);
      EXPECT_NEAR(at.h_mm, depth, 1e-9);
      const FlankFoundationPoint p = flank_foundation_point(at, reference_depth, k);
      EXPECT_NEAR(p.b_N_mm3.dot(n), k * 0.07, 1e-9 * k);  // outward, k (h − h_ref)
      EXPECT_NEAR((p.db_dx_N_mm4 - p.db_dx_N_mm4.transpose()).norm(), 0.0, 1e-15);  // a gradient field
      auto b = [&](const Eigen::Vector2d& y) {
        return flank_foundation_point(curve.coordinates(y.x(), y.y(), starts, s), reference_depth, k).b_N_mm3;
      };
      for (int j = 0; j < 2; ++j) {
        const Eigen::Vector2d e = Eigen::Vector2d::Unit(j) * h;
        const Eigen::Vector2d fd = (b(x + e) - b(x - e)) / (2.0 * h);
        EXPECT_LT((fd - p.db_dx_N_mm4.col(j)).norm(), 1e-7 * k) << "s " << s << " depth " << depth << " column " << j;
      }
      // The curvature term is there: k δ K / (1 − K h) along the tangent.
      const Eigen::Vector2d t(std::cos(at.phi_rad), -std::sin(at.phi_rad));
      EXPECT_NEAR(t.dot(p.db_dx_N_mm4 * t), k * 0.07 * at.K_1_mm / (1.0 - at.K_1_mm * depth), 1e-12);
      ++points;
    }
  EXPECT_EQ(points, 30);
  EXPECT_NEAR(flank_stiffness_N_mm4(11.86, 19.0 * M_PI / 180.0, 11.1542), 0.04521, 1e-5);  // the thesis cards' bottom
}

TEST(SegmentFlank, BlockMovedUniformlyDeeperCarriesKTimesTheDepthChangeTimesItsVolume) {
  // Every node of the block moved by Δ away from the cord line: a rigid motion (no stress), each
  // point Δ deeper, so the foundation pushes back with k Δ per unit volume, k Δ V in all.
  const Mesh m = strip();
  const auto law = make_elastic(ElasticLaw::hencky, 10.0, 0.3);
  const double k = 0.08, delta = 0.05, volume = kHeight_mm * 2.0 * m.half_length_mm;
  StaticProblem p;
  p.mesh = &m;
  p.laws = {law.get(), law.get()};
  // Every node's radial component prescribed, the cord line's both (the others free along x, where
  // neither the stress-free block nor the foundation pushes).
  for (int n = 0; n < m.node_count(); ++n) p.constraints.push_back({n, 0.0, {m.X[n].y() == 0.0, true}});
  p.prescribe = [delta](double lambda, std::vector<std::array<double, 2>>& v) {
    for (auto& x : v) x = {0.0, -lambda * delta};
  };
  p.following_force = straight_foundation(m, k);
  const StaticSolution s = solve_static(p, SolverKnobs{});
  Eigen::Vector2d reactions = Eigen::Vector2d::Zero(), foundation = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& r : s.reaction_N_mm) reactions += r;
  for (const Eigen::Vector2d& f : s.following_N_mm) foundation += f;
  EXPECT_NEAR(foundation.y(), k * delta * volume, 1e-12 * k * delta * volume);
  EXPECT_NEAR(foundation.x(), 0.0, 1e-14);
  EXPECT_NEAR(reactions.y(), -k * delta * volume, 1e-9 * k * delta * volume);
  EXPECT_NEAR(reactions.x(), 0.0, 1e-12);
  ASSERT_EQ(s.following_N_mm.size(), static_cast<std::size_t>(m.element_count()));
}

TEST(SegmentFlank, LayerOnTheFoundationUnderAUniformRadialLoadIsAWinklerSupportedBar) {
  // The strip held at its cord line, its ends sliding along the radial lines, pushed outwards by a
  // uniform b0 (Report I's dead radial load): uniaxial strain, so its upward motion v(y) solves
  // M v'' − k v + b0 = 0 with v(0) = 0 and σ_yy = 0 at the bottom:
  //   v = (b0/k) [1 − cosh(α(y + H)) / cosh(αH)],  α = √(k/M),  M = E(1 − ν)/((1 + ν)(1 − 2ν)).
  const Mesh m = strip();
  const double E = 10.0, nu = 0.3, M = E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double k = M / (kHeight_mm * kHeight_mm), b0 = 1e-4 * M / kHeight_mm;  // αH = 1, strains ~ 10⁻⁴
  const auto law = make_elastic(ElasticLaw::hencky, E, nu);
  StaticProblem p = test::held_strip(m, *law, {true, false});
  p.body_force = [&m, b0](double lambda, std::vector<Eigen::Vector2d>& b) {
    b.assign(m.element_count(), Eigen::Vector2d(0.0, lambda * b0));
  };
  p.following_force = straight_foundation(m, k);
  SolverKnobs knobs;
  knobs.steps = 2;
  const StaticSolution s = solve_static(p, knobs);
  const double alpha = std::sqrt(k / M);
  auto closed_form = [&](double y) { return b0 / k * (1.0 - std::cosh(alpha * (y + kHeight_mm)) / std::cosh(alpha * kHeight_mm)); };
  double worst = 0.0;
  for (int n = 0; n < m.node_count(); ++n) worst = std::max(worst, std::abs(s.u_mm[n].y() - closed_form(m.X[n].y())));
  const double v_bottom = closed_form(-kHeight_mm);
  EXPECT_LT(worst, 2e-3 * v_bottom) << worst / v_bottom;
  // Without the foundation the bottom would rise b0 H²/(2M), 1.42 × as far (1 − 1/cosh 1 = 0.352).
  EXPECT_LT(v_bottom, 0.71 * b0 * kHeight_mm * kHeight_mm / (2.0 * M));
  // The foundation's tangent is assembled: the near-linear problem converges in ≤ 2 Newton
  // iterations per increment after the predictor (a dead foundation would contract by k/(k + K) only).
  EXPECT_LE(s.newton_iterations, 3 * s.increments);
  // Σ reactions + ∫ b dV + ∫ b_foundation dV = 0.
  Eigen::Vector2d total = Eigen::Vector2d(0.0, b0 * kHeight_mm * 2.0 * m.half_length_mm);
  for (const Eigen::Vector2d& r : s.reaction_N_mm) total += r;
  for (const Eigen::Vector2d& f : s.following_N_mm) total += f;
  EXPECT_LT(total.norm(), 1e-9 * b0 * kHeight_mm * 2.0 * m.half_length_mm);
}
