// Element validation (issue 11 item 6): patch test, bending against beam theory at ν = 0.4995,
// and the locking of a fully integrated bilinear displacement element.
#include <cmath>
#include <cstdio>
#include <set>

#include <Eigen/SVD>
#include <gtest/gtest.h>

#include "fitlib/core/error.hpp"
#include "fitlib/segment/elastic.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/solver.hpp"
#include "fitlib/segment/static_case.hpp"
#include "../../../fitlib/src/segment/element.hpp"

using namespace fitlib::segment;

namespace {

CogSection strip(double height, double length) {
  CogSection s;
  s.height_mm = height;
  s.cushion_mm = 0.5 * height;
  s.cog_depth_mm = 0.0;
  s.root_fillet_mm = s.tip_radius_mm = 0.0;
  s.cog_pitch_mm = length;
  return s;
}

// All boundary nodes of the mesh: top, ends and bottom edges.
std::vector<int> boundary_nodes(const Mesh& m) {
  std::set<int> b(m.top_nodes.begin(), m.top_nodes.end());
  b.insert(m.left_nodes.begin(), m.left_nodes.end());
  b.insert(m.right_nodes.begin(), m.right_nodes.end());
  for (const Edge& e : m.bottom_edges)
    for (int a : e.nodes)
      if (a >= 0) b.insert(a);
  return {b.begin(), b.end()};
}

}  // namespace

namespace {

// The cogged mesh has distorted, curved-edge elements; a homogeneous F on the boundary must be
// reproduced inside exactly, with the stress of the law at F everywhere.
MeshKnobs patch_mesh() {
  MeshKnobs k;
  k.central_pitches = 1.0, k.end_pitches = 0.5, k.fine_size_mm = 0.6, k.coarse_size_mm = 1.5;
  return k;
}

StaticSolution expect_patch_exact(Integration integration, const MeshKnobs& k = patch_mesh()) {
  const Mesh m = build_mesh(CogSection{}, k);
  Eigen::Matrix2d F;
  F << 1.06, 0.03, -0.02, 0.95;
  const auto law = make_elastic(ElasticLaw::neo_hookean, 20.0, 0.49);
  StaticProblem p;
  p.mesh = &m;
  p.laws = {law.get(), law.get()};
  for (int n : boundary_nodes(m)) p.constraints.push_back({n, 0.0, {true, true}});
  p.motion = prescribed([&](double lambda, std::vector<std::array<double, 2>>& v) {
    const Eigen::Matrix2d Fl = Eigen::Matrix2d::Identity() + lambda * (F - Eigen::Matrix2d::Identity());
    for (std::size_t c = 0; c < p.constraints.size(); ++c) {
      const Eigen::Vector2d u = (Fl - Eigen::Matrix2d::Identity()) * m.X[p.constraints[c].node];
      v[c] = {u.x(), u.y()};
    }
  });
  SolverKnobs knobs;
  knobs.stepping.steps = 2;
  knobs.physics.integration = integration;
  const StaticSolution s = solve_static(p, knobs);
  double worst_u = 0.0, worst_s = 0.0;
  const PointResponse exact = law->respond(F);
  const Eigen::Matrix2d sigma = exact.P * F.transpose() / F.determinant();
  for (int a = 0; a < m.node_count(); ++a)
    worst_u = std::max(worst_u, (s.u_mm[a] - (F - Eigen::Matrix2d::Identity()) * m.X[a]).norm());
  for (const auto& el : s.points)
    for (const auto& g : el) worst_s = std::max(worst_s, (g.cauchy_MPa - sigma).cwiseAbs().maxCoeff());
  EXPECT_LT(worst_u, 1e-12) << to_string(integration);
  EXPECT_LT(worst_s, 1e-10 * sigma.cwiseAbs().maxCoeff()) << to_string(integration);
  return s;
}

}  // namespace

TEST(SegmentElement, FiniteStrainPatchTestIsExactToRoundOff) { expect_patch_exact(Integration::reduced); }

// The run's cost counters: where Newton converges without a rejected step, every iteration is one
// element loop and each increment ends with the loop that shows it converged.
TEST(SegmentElement, AnIncrementCostsOneElementLoopPerIterationAndOneToConverge) {
  const StaticSolution s = expect_patch_exact(Integration::reduced);
  EXPECT_EQ(s.cuts, 0);
  EXPECT_EQ(s.factorizations, s.newton_iterations);
  EXPECT_EQ(s.assemblies, s.newton_iterations + s.increments);
}

// The assembly predicted to show convergence is made without the tangent (Newton::predicted_converged):
// on the R = 40 mm bend every increment's last assembly is one, none was predicted wrongly (no
// assembly repeated with the tangent: one loop per iteration and one to converge), and the stresses
// are the converged ones (the residual does not depend on the tangent).
TEST(SegmentElement, TheAssemblyThatShowsConvergenceIsMadeWithoutTheTangent) {
  StaticSetup setup;
  setup.solver.stepping.steps = 4;
  setup.mesh.fine_size_mm = 1.0, setup.mesh.coarse_size_mm = 2.5;
  const StaticResult bend = run_static_case(setup, {0.0, 1.0 / 40.0, 0.0});
  std::printf("bend: %d increments, %d iterations, %d assemblies, %d without the tangent\n", bend.increments,
              bend.newton_iterations, bend.assemblies, bend.residual_only_assemblies);
  EXPECT_EQ(bend.residual_only_assemblies, bend.increments);
  EXPECT_EQ(bend.assemblies, bend.newton_iterations + bend.increments);
}

// The graded mesh (docs/segment.md §Mesh: narrow columns at the gap, rows growing from the
// profile) keeps the element exact: grading only moves nodes, the edges stay straight or on the profile.
TEST(SegmentElement, GradedMeshPassesTheFiniteStrainPatchTestToRoundOff) {
  MeshKnobs k = patch_mesh();
  k.fine_size_mm = 1.0, k.coarse_size_mm = 2.5, k.cushion_rows = 1;
  k.gap_size_mm = 0.3, k.column_growth = 0.25, k.row_growth = 1.1;  // the life mesh's grading
  expect_patch_exact(Integration::reduced, k);
  expect_patch_exact(Integration::fbar, k);
}

TEST(SegmentElement, FbarElementPassesTheFiniteStrainPatchTestToRoundOff) {
  // F̄ = F when F is homogeneous (J̄ = J everywhere), so the patch is exact as for CPE8R.
  expect_patch_exact(Integration::fbar);
}

namespace {

// Pure bending of a straight plane-strain strip (height h, length L): end faces u_x = K x y'
// (y' from mid-height), u_y free; one node holds u_y. Beam theory: M = E/(1 − ν²) h³/12 K.
double bending_moment_ratio(int nodes_per_element, Integration integration, double nu, double size_mm) {
  const double h = 2.0, L = 20.0, K = 0.004, E = 10.0;
  MeshKnobs k;
  k.central_pitches = 1.0, k.end_pitches = 0.0, k.fine_size_mm = size_mm, k.cushion_rows = 2;
  k.nodes_per_element = nodes_per_element;
  k.coarse_size_mm = size_mm;
  const Mesh m = build_mesh(strip(h, L), k);
  const auto law = make_elastic(ElasticLaw::st_venant_kirchhoff, E, nu);
  StaticProblem p;
  p.mesh = &m;
  p.laws = {law.get(), law.get()};
  int anchor = -1;
  for (int side = 0; side < 2; ++side)
    for (int n : side == 0 ? m.left_nodes : m.right_nodes) {
      const bool mid = std::abs(m.X[n].y() + 0.5 * h) < 1e-12;
      p.constraints.push_back({n, 0.0, {true, side == 0 && mid}});
      if (side == 0 && mid) anchor = n;
    }
  EXPECT_GE(anchor, 0);
  p.motion = prescribed([&](double lambda, std::vector<std::array<double, 2>>& v) {
    for (std::size_t c = 0; c < p.constraints.size(); ++c) {
      const Eigen::Vector2d& X = m.X[p.constraints[c].node];
      v[c] = {lambda * K * X.x() * (X.y() + 0.5 * h), 0.0};
    }
  });
  SolverKnobs knobs;
  knobs.stepping.steps = 1;
  knobs.physics.integration = integration;
  const StaticSolution s = solve_static(p, knobs);
  int mid = -1;
  for (int a = 0; a < m.node_count(); ++a)
    if (std::abs(m.X[a].x()) < 1e-12 && std::abs(m.X[a].y() + 0.5 * h) < 1e-12) mid = a;
  const SectionForce f = section_force(p, s, 0.0, m.X[mid] + s.u_mm[mid], integration);
  const double beam = E / (1.0 - nu * nu) * h * h * h / 12.0 * K;
  return f.moment_N / beam;
}

}  // namespace

TEST(SegmentElement, QuadraticReducedElementBendsLikeBeamTheoryNearIncompressibility) {
  const double ratio = bending_moment_ratio(8, Integration::reduced, 0.4995, 0.5);
  std::printf("Q8 reduced, nu 0.4995: M/M_beam = %.5f\n", ratio);
  EXPECT_NEAR(ratio, 1.0, 0.02);
}

TEST(SegmentElement, FullyIntegratedBilinearElementLocksNearIncompressibility) {
  // Same strip, same mesh density in nodes: the 4-node element with full 2×2 integration is
  // acceptable at ν = 0.3 but its bending mode carries volume change, so at ν = 0.4995 the
  // moment is many times too large (volumetric locking).
  const double compressible = bending_moment_ratio(4, Integration::full, 0.3, 0.25);
  const double nearly_incompressible = bending_moment_ratio(4, Integration::full, 0.4995, 0.25);
  std::printf("Q4 full: M/M_beam = %.4f at nu 0.3, %.3f at nu 0.4995\n", compressible, nearly_incompressible);
  EXPECT_LT(std::abs(compressible - 1.0), 0.1);
  EXPECT_GT(nearly_incompressible, 3.0);
  EXPECT_NEAR(bending_moment_ratio(8, Integration::reduced, 0.4995, 0.5), 1.0, 0.02);
}

TEST(SegmentElement, FbarQuadraticElementBendsLikeBeamTheoryNearIncompressibility) {
  // F-bar keeps the reduced rule's volumetric constraint count: no locking at ν = 0.4995, where
  // the fully integrated Q8 is too stiff.
  const double fbar = bending_moment_ratio(8, Integration::fbar, 0.4995, 0.5);
  const double full = bending_moment_ratio(8, Integration::full, 0.4995, 0.5);
  std::printf("Q8 nu 0.4995: M/M_beam = %.5f F-bar, %.5f full 3x3\n", fbar, full);
  EXPECT_NEAR(fbar, 1.0, 0.02);
}

namespace {

// Zero singular values (relative 1e-10) of one distorted 8-node element's tangent at the
// reference state: the null space of the linearised element.
int zero_modes(Integration integration) {
  const std::vector<Eigen::Vector2d> X = {{0, 0}, {1.2, 0.1}, {1.1, 0.9}, {-0.1, 1.0},
                                          {0.6, 0.02}, {1.2, 0.5}, {0.5, 0.97}, {-0.05, 0.5}};
  const std::vector<Eigen::Vector2d> u(8, Eigen::Vector2d::Zero());
  const auto law = make_elastic(ElasticLaw::neo_hookean, 10.0, 0.49);
  const auto rule = detail::gauss_rule(integration == Integration::reduced ? 2 : 3);
  const detail::ElementStep step{};
  detail::ElementVector f;
  detail::ElementMatrix K;
  EXPECT_TRUE(detail::element_response(X, u, *law, rule, step, f, &K, nullptr, integration == Integration::fbar));
  const Eigen::MatrixXd Kd = K;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Kd);
  const Eigen::VectorXd sv = svd.singularValues();
  int zeros = 0;
  for (int i = 0; i < sv.size(); ++i) zeros += sv(i) < 1e-10 * sv(0);
  std::printf("%s: smallest singular values %.3e %.3e %.3e %.3e (largest %.3e)\n", to_string(integration),
              sv(sv.size() - 1), sv(sv.size() - 2), sv(sv.size() - 3), sv(sv.size() - 4), sv(0));
  return zeros;
}

}  // namespace

TEST(SegmentElement, FbarElementHasOnlyTheThreeRigidModesWhereCpe8rHasAFourth) {
  EXPECT_EQ(zero_modes(Integration::fbar), 3);
  EXPECT_EQ(zero_modes(Integration::full), 3);
  // CPE8R: 2 translations, 1 rotation and the 2×2 rule's hourglass (spurious) mode.
  EXPECT_EQ(zero_modes(Integration::reduced), 4);
}

TEST(SegmentElement, FbarTangentIsUnsymmetricAndTheSolverUsesLu) {
  EXPECT_FALSE(symmetric_tangent(Integration::fbar));
  EXPECT_TRUE(symmetric_tangent(Integration::reduced));
  EXPECT_TRUE(symmetric_tangent(Integration::full));
  EXPECT_EQ(integration_from_string("fbar"), Integration::fbar);
  EXPECT_STREQ(to_string(integration_from_string("full")), "full");
  EXPECT_THROW(integration_from_string("bbar"), fitlib::core::UsageError);
}

// The rotated predictor (docs/segment.md §Solver): bending the segment to R = 40 mm in 4 increments
// turns its ends by 0.17 rad; a linearised turn strains the ν = 0.4995 rubber by θ²/2. With the
// rotation's second-order part added to the predictor Newton needs fewer iterations, and the
// converged stresses are the same (the start changes, not the equations).
TEST(SegmentElement, RotatedPredictorSavesIterationsAndKeepsTheSolution) {
  StaticSetup setup;
  setup.solver.newton.linearised_pressure = false;  // the predictor's own effect (the pressure's: below)
  setup.solver.stepping.rotated_predictor = true;
  setup.solver.stepping.steps = 4;
  setup.mesh.fine_size_mm = 1.0, setup.mesh.coarse_size_mm = 2.5;
  const StaticLoad bend{0.0, 1.0 / 40.0, 0.0};
  const StaticResult rotated = run_static_case(setup, bend);
  setup.solver.stepping.rotated_predictor = false;
  const StaticResult linear = run_static_case(setup, bend);
  std::printf("Newton iterations: rotated predictor %d, linear %d\n", rotated.newton_iterations, linear.newton_iterations);
  EXPECT_LT(rotated.newton_iterations, linear.newton_iterations);
  for (std::size_t k = 0; k < rotated.stresses.size(); ++k) {
    EXPECT_NEAR(rotated.stresses[k].sigma22_MPa, linear.stresses[k].sigma22_MPa, 1e-7 * std::abs(linear.stresses[k].sigma22_MPa));
    EXPECT_NEAR(rotated.stresses[k].sigma12_MPa, linear.stresses[k].sigma12_MPa, 1e-7 * std::abs(linear.stresses[k].sigma22_MPa));
  }
}

// The linearised pressure (NewtonOptions::linearised_pressure; docs/segment.md §"Cost (reference)"):
// after a step the plain tangent's pressure term carries κ det ΔF, a spurious pressure of the
// ν = 0.4995 rubber (κ/μ ≈ 10³) that turns the next step; at the pressure linearised over the step
// Newton needs fewer than half the iterations on the same bend (from the linear predictor, against
// the plain pressure from the rotated one), and the residual is the same, so are the converged stresses.
TEST(SegmentElement, LinearisedPressureSavesIterationsAndKeepsTheSolution) {
  StaticSetup setup;
  setup.solver.stepping.steps = 4;
  setup.mesh.fine_size_mm = 1.0, setup.mesh.coarse_size_mm = 2.5;
  const StaticLoad bend{0.0, 1.0 / 40.0, 0.0};
  const StaticResult linearised = run_static_case(setup, bend);  // the defaults: the linear predictor
  setup.solver.newton.linearised_pressure = false;
  setup.solver.stepping.rotated_predictor = true;  // the plain pressure's best predictor
  const StaticResult plain = run_static_case(setup, bend);
  std::printf("Newton iterations: linearised pressure %d, plain %d\n", linearised.newton_iterations, plain.newton_iterations);
  EXPECT_LT(2 * linearised.newton_iterations, plain.newton_iterations);
  for (std::size_t k = 0; k < plain.stresses.size(); ++k) {
    EXPECT_NEAR(linearised.stresses[k].sigma22_MPa, plain.stresses[k].sigma22_MPa, 1e-7 * std::abs(plain.stresses[k].sigma22_MPa));
    EXPECT_NEAR(linearised.stresses[k].sigma12_MPa, plain.stresses[k].sigma12_MPa, 1e-7 * std::abs(plain.stresses[k].sigma22_MPa));
  }
}
