// Implicit dynamics of the segment (PhysicsOptions::inertia, segment/inertia.hpp; docs/segment.md
// "Inertia"): lumped masses, and a strip's shear vibration under a sudden load against the closed
// form of its fundamental mode; a slow load gives the static solution.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "../../../fitlib/src/segment/inertia.hpp"
#include "fitlib/segment/elastic.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/solver.hpp"
#include "fitlib/segment/static_case.hpp"
#include "strip.hpp"
#include <Eigen/Geometry>

using namespace fitlib::segment;

namespace {

constexpr double kHeight_mm = test::kStripHeight_mm, kE_MPa = 10.0, kNu = 0.3, kRho_t_mm3 = 1.2e-9;
constexpr double kG_MPa = kE_MPa / (2.0 * (1.0 + kNu));

using test::strip;

// The strip's top held, its end faces free along x and held in y, a uniform body force b_x from
// λ > 0 on (a sudden load) or growing with λ (`ramp`); time t = λ t_end. Pure shear u_x(y) is then
// exact: the fundamental mode's period is 4H/c, c = √(G/ρ) (a layer fixed on one face).
struct ShearRun {
  std::vector<double> t_s, u_bottom_mm;
  StaticSolution solution;
};

ShearRun shear_run(const Mesh& m, double b_N_mm3, double t_end_s, int steps, bool ramp, bool inertia) {
  const auto law = make_elastic(ElasticLaw::hencky, kE_MPa, kNu);
  StaticProblem p = test::held_strip(m, *law, {false, true});
  p.loads.push_back(dead_body_force(m.element_count(), [&](double lambda, std::vector<Eigen::Vector2d>& b) {
    b.assign(m.element_count(), Eigen::Vector2d(ramp ? lambda * b_N_mm3 : b_N_mm3, 0.0));
  }));
  p.time_s = [t_end_s](double lambda) { return lambda * t_end_s; };
  p.density_t_mm3 = kRho_t_mm3;
  int bottom = 0;  // the bottom node at x = 0
  for (int n = 0; n < m.node_count(); ++n)
    if (std::abs(m.X[n].x()) < 1e-9 && m.X[n].y() < m.X[bottom].y() + 1e-9) bottom = n;
  ShearRun out;
  CallbackObserver watch([&](double lambda, const StaticSolution& s) {
    out.t_s.push_back(lambda * t_end_s);
    out.u_bottom_mm.push_back(s.u_mm[bottom].x());
  });
  p.observers.push_back(&watch);
  SolverKnobs knobs;
  knobs.stepping.steps = steps;
  knobs.physics.inertia = inertia;
  out.solution = solve_static(p, knobs);
  return out;
}

// Times at which u crosses `level` going up, by linear interpolation between samples.
std::vector<double> upward_crossings(const ShearRun& r, double level) {
  std::vector<double> t;
  for (std::size_t k = 1; k < r.t_s.size(); ++k) {
    const double a = r.u_bottom_mm[k - 1] - level, b = r.u_bottom_mm[k] - level;
    if (a < 0.0 && b >= 0.0) t.push_back(r.t_s[k - 1] + (r.t_s[k] - r.t_s[k - 1]) * a / (a - b));
  }
  return t;
}

}  // namespace

TEST(SegmentInertia, LumpedMassesArePositiveAndDiagonallyScaled) {
  for (int npe : {4, 8}) {
    const Mesh m = strip(npe);
    const std::vector<double> mass = detail::lumped_masses(m, kRho_t_mm3);
    double total = 0.0;
    for (double v : mass) {
      EXPECT_GT(v, 0.0);
      total += v;
    }
    EXPECT_NEAR(total, kRho_t_mm3 * kHeight_mm * 2.0 * m.half_length_mm, 1e-12 * total) << npe;
  }
  // One rectangular 8-node element: diagonal scaling gives each corner 3/76 of its mass and each
  // midside 16/76 (row sums would give the corners −1/12).
  Mesh one;
  one.nodes_per_element = 8;
  one.X = {{0, 0}, {2, 0}, {2, 1}, {0, 1}, {1, 0}, {2, 0.5}, {1, 1}, {0, 0.5}};
  one.elements = {{0, 1, 2, 3, 4, 5, 6, 7}};
  one.roles = {Role::bottom};
  const std::vector<double> mass = detail::lumped_masses(one, 1.0);
  for (int a = 0; a < 8; ++a) EXPECT_NEAR(mass[a], 2.0 * (a < 4 ? 3.0 / 76.0 : 16.0 / 76.0), 1e-13) << a;
}

TEST(SegmentInertia, SuddenShearLoadVibratesWithTheStripsFundamentalPeriodAboutTheStaticSolution) {
  const Mesh m = strip(8);
  const double c_mm_s = std::sqrt(kG_MPa / kRho_t_mm3), period_s = 4.0 * kHeight_mm / c_mm_s;
  const double b = 1e-4 * kG_MPa / kHeight_mm;  // shear strain 10⁻⁴ at the top: linear
  const double u_static = b * kHeight_mm * kHeight_mm / (2.0 * kG_MPa);
  const ShearRun r = shear_run(m, b, 3.0 * period_s, 600, false, true);  // Δt = T/200
  // Every mode of the step response, u_s (1 − Σ c_k cos((2k − 1) ω t)), crosses the static value at
  // T/4, 3T/4, …: the upward crossings at T/4, 5T/4, 9T/4.
  const std::vector<double> up = upward_crossings(r, u_static);
  ASSERT_GE(up.size(), 3u);
  EXPECT_NEAR(up[0], 0.25 * period_s, 0.01 * period_s);
  EXPECT_NEAR(up[1] - up[0], period_s, 0.01 * period_s);
  EXPECT_NEAR(up[2] - up[1], period_s, 0.01 * period_s);
  // A sudden load overshoots to twice the static displacement (less backward Euler's damping,
  // ≈ 5 % of the amplitude over the first half period at Δt = T/200).
  double first_peak = 0.0;
  for (std::size_t k = 0; k < r.t_s.size() && r.t_s[k] < period_s; ++k) first_peak = std::max(first_peak, r.u_bottom_mm[k]);
  EXPECT_GT(first_peak / u_static, 1.9);
  EXPECT_LT(first_peak / u_static, 2.02);
  // Without inertia the same load gives the static solution at once.
  const ShearRun quasi = shear_run(m, b, 3.0 * period_s, 4, false, false);
  EXPECT_NEAR(quasi.u_bottom_mm.back() / u_static, 1.0, 0.01);
  // Σ reactions + ∫ b dV − Σ m·a = 0: the inertia force is reported.
  Eigen::Vector2d reactions = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& f : r.solution.reaction_N_mm) reactions += f;
  const double applied = b * kHeight_mm * 2.0 * m.half_length_mm;
  Eigen::Vector2d inertia = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& f : r.solution.inertia_N_mm) inertia += f;
  EXPECT_NEAR(reactions.x() + applied - inertia.x(), 0.0, 1e-8 * applied);
  EXPECT_GT(std::abs(inertia.x()), 0.05 * applied);  // still vibrating at 3T
}

TEST(SegmentInertia, SlowLoadGivesTheStaticSolution) {
  const Mesh m = strip(8);
  const double period_s = 4.0 * kHeight_mm / std::sqrt(kG_MPa / kRho_t_mm3);
  const double b = 1e-4 * kG_MPa / kHeight_mm;
  const ShearRun slow = shear_run(m, b, 100.0 * period_s, 50, true, true);
  const ShearRun quasi = shear_run(m, b, 100.0 * period_s, 50, true, false);
  EXPECT_NEAR(slow.u_bottom_mm.back() / quasi.u_bottom_mm.back(), 1.0, 2e-3);
  EXPECT_NEAR(quasi.u_bottom_mm.back() / (b * kHeight_mm * kHeight_mm / (2.0 * kG_MPa)), 1.0, 0.01);
}

TEST(SegmentInertia, CordFramesCarryABentStripsNodesAsItsSolutionDoes) {
  // The motion the inertia is measured against (PrescribedMotion::frame_motion): each node carried
  // with its column's cord point and tangent. On a static bend to R = 40 mm it is the prescribed
  // motion on the cord line and, below it, the FE solution up to the section's own strain (plane
  // sections stay plane); turned the wrong way it would be off by twice the turn.
  const Mesh m = strip(8);
  const auto law = make_elastic(ElasticLaw::hencky, kE_MPa, 0.45);
  const StaticProblem p = static_problem(m, {law.get(), law.get()}, {0.0, 1.0 / 40.0, 0.0}, EndCondition::radial);
  const StaticSolution s = solve_static(p, SolverKnobs{});
  std::vector<Eigen::Vector2d> frame;
  p.motion->frame_motion(1.0, frame);
  double worst = 0.0, worst_reversed = 0.0;
  for (int n = 0; n < m.node_count(); ++n) {
    const double th = -m.X[n].x() / 40.0;  // the cord tangent's turn at the column (clockwise)
    const Eigen::Vector2d offset = m.X[n] - Eigen::Vector2d(m.X[n].x(), 0.0);
    const Eigen::Vector2d reversed = frame[n] + (Eigen::Rotation2Dd(-th).toRotationMatrix() - Eigen::Rotation2Dd(th).toRotationMatrix()) * offset;
    worst = std::max(worst, (s.u_mm[n] - frame[n]).norm());
    worst_reversed = std::max(worst_reversed, (s.u_mm[n] - reversed).norm());
  }
  for (int n : m.top_nodes) EXPECT_LT((s.u_mm[n] - frame[n]).norm(), 1e-12);
  EXPECT_LT(worst, 0.25 * worst_reversed) << worst << " " << worst_reversed;
}
