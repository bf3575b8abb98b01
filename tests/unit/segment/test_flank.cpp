// The deformation-limited flank contact (segment/flank.hpp; docs/segment.md "Flank foundation"): the
// foundation's force and tangent at a point against central differences on a curved, strained cord
// curve; a block moved uniformly deeper carries k Δh V; a layer on the foundation under a uniform
// radial load against the closed form of a Winkler-supported bar, with Newton's quadratic rate.
// The tangential flank's stick (docs/segment.md "Tangential flank"): its force and tangent against
// central differences together with the radial part, the committed slip; a block pulled along the
// belt through stick, slip and elastic unloading; a free block under a load along the belt sticks
// at load / k_t and has no equilibrium beyond the limit. The sliding friction's direction: force
// and tangent against central differences; a block under a load along the belt creeps at the
// Coulomb velocity.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "fitlib/core/error.hpp"
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
LoadPtr straight_foundation(const Mesh& m, double k) {
  std::vector<double> path_x;
  for (const Eigen::Vector2d& X : m.X) path_x.push_back(X.x());
  const NeutralCurve line = NeutralCurve::uniform(0.0, 0.0, 1.5 * m.half_length_mm);
  return flank_foundation(m, path_x, Integration::reduced, line, [line](double) { return line; },
                          [k, &m](double, std::vector<double>& per_element) { per_element.assign(m.element_count(), k); });
}

// The strip's stick (and radial k) on a cord curve that stays put, the same values in every element.
LoadPtr stick_contact(const Mesh& m, const NeutralCurve& curve, double k, double k_t, double limit) {
  std::vector<double> path_x;
  for (const Eigen::Vector2d& X : m.X) path_x.push_back(X.x());
  const NeutralCurve line = NeutralCurve::uniform(0.0, 0.0, 1.5 * m.half_length_mm);
  return flank_contact(m, path_x, Integration::reduced, line, [curve](double) { return curve; }, true, false, false,
                       [&m, k, k_t, limit](double, FlankLevels& l) {
                         l.radial_N_mm4.assign(m.element_count(), k);
                         l.stick_N_mm4.assign(m.element_count(), k_t);
                         l.stick_limit_N_mm3.assign(m.element_count(), limit);
                       });
}

// Free along x everywhere, one corner held in y too: the block moves along the belt only against
// the stick.
StaticProblem block_along_the_belt(const Mesh& m, const PlaneStrainLaw& law, bool x_prescribed) {
  StaticProblem p;
  p.mesh = &m;
  p.laws = {&law, &law};
  for (int n = 0; n < m.node_count(); ++n)
    if (x_prescribed || n == m.top_nodes.front()) p.constraints.push_back({n, 0.0, {x_prescribed, n == m.top_nodes.front()}});
  return p;
}

}  // namespace

TEST(SegmentFlank, StickForceAndTangentMatchCentralDifferencesAndTheSlipIsCommitted) {
  // The stick law at a point: stick −k_t (w − w_s), slip ∓limit, and the slip that reproduces it.
  const double k_t = 0.3, limit = 0.02;
  const FlankStickPoint stick = flank_stick_point(0.05, 0.01, k_t, limit), slip = flank_stick_point(0.2, 0.01, k_t, limit);
  EXPECT_FALSE(stick.slipping);
  EXPECT_DOUBLE_EQ(stick.B_t_N_mm3, -k_t * 0.04);
  EXPECT_DOUBLE_EQ(stick.slip_after_mm, 0.01);
  EXPECT_TRUE(slip.slipping);
  EXPECT_DOUBLE_EQ(slip.B_t_N_mm3, -limit);
  EXPECT_EQ(slip.dB_dw_N_mm4, 0.0);
  EXPECT_NEAR(-k_t * (0.2 - slip.slip_after_mm), -limit, 1e-15);
  EXPECT_EQ(flank_stick_point(0.2, 0.01, k_t, 0.0).B_t_N_mm3, 0.0);  // no unused friction: Report I's alone
  EXPECT_EQ(flank_stick_point(0.2, 0.01, k_t, 0.0).slip_after_mm, 0.2);
  EXPECT_NEAR(flank_stick_stiffness_N_mm4(11.86 / 4.0, 11.1542), 0.2860, 1e-4);  // the thesis cards' bottom

  // The following force on a curved, strained cord curve, with the radial foundation: b and ∂b/∂x
  // against central differences where the points stick and where they slip.
  const Mesh m = strip();
  const std::vector<double> K_pos{0.02, 0.035, 0.0}, eps_pos{0.01, 0.012, 0.02, 0.015};
  const std::vector<double> K_neg{0.02, 0.0, 0.03}, eps_neg{0.01, 0.008, 0.0, 0.02};
  const NeutralCurve curve(3.0, K_pos, eps_pos, K_neg, eps_neg);
  const double k = 0.05, h = 1e-6, wide = 0.1;  // wide: stick within ±0.33 mm of the column
  const LoadPtr f = stick_contact(m, curve, k, k_t, wide);
  f->prepare(1.0);
  const int points = 4;  // reduced rule on the 8-node strip: 2 × 2
  int checked = 0, slipped = 0;
  for (int e = 0; e < m.element_count(); e += 3)
    for (int g = 0; g < points; ++g) {
      // The point's column: the element's centre column is near enough for a position to test.
      double X = 0.0;
      for (int a = 0; a < 4; ++a) X += 0.25 * m.X[m.elements[e][a]].x();
      const CurvePoint c = curve.at(curve.s_from_unstrained(X));
      const Eigen::Vector2d n(std::sin(c.phi_rad), std::cos(c.phi_rad));
      const Eigen::Vector2d x = Eigen::Vector2d(c.x_mm, c.y_mm) - (1.0 + 0.4 * g) * n + 0.1 * (e % 7 - 3) * Eigen::Vector2d(1.0, 0.3);
      Eigen::Vector2d b, b_plus, b_minus;
      Eigen::Matrix2d db, unused;
      ASSERT_TRUE(f->at_point(e, g, x, b, db));
      EXPECT_NEAR((db - db.transpose()).norm(), 0.0, 1e-15);  // a gradient field at the committed slip
      for (int j = 0; j < 2; ++j) {
        const Eigen::Vector2d step = Eigen::Vector2d::Unit(j) * h;
        f->at_point(e, g, x + step, b_plus, unused), f->at_point(e, g, x - step, b_minus, unused);
        EXPECT_LT(((b_plus - b_minus) / (2.0 * h) - db.col(j)).norm(), 1e-7 * k_t) << "element " << e << " point " << g;
      }
      // Without the radial part the force is along the column's tangent, −k_t w or ∓limit.
      Eigen::Vector2d radial_b;
      Eigen::Matrix2d radial_db;
      const LoadPtr radial = stick_contact(m, curve, k, 0.0, wide);
      radial->prepare(1.0);
      radial->at_point(e, g, x, radial_b, radial_db);
      const double along = (b - radial_b).norm();
      EXPECT_TRUE(std::abs(along - wide) < 1e-15 || along < wide) << along;
      slipped += std::abs(along - wide) < 1e-15;
      ++checked;
    }
  EXPECT_GT(checked, 20);
  EXPECT_GT(slipped, 0);
  EXPECT_LT(slipped, checked);

  // Committed where it slips, the point keeps its force there and unloads elastically.
  const int e = 0, g = 0;
  Eigen::Vector2d b0, b1, b2;
  Eigen::Matrix2d db0;
  const LoadPtr only = stick_contact(m, curve, 0.0, k_t, limit);
  only->prepare(1.0);
  double X = 0.0;
  for (int a = 0; a < 4; ++a) X += 0.25 * m.X[m.elements[e][a]].x();
  const CurvePoint c = curve.at(curve.s_from_unstrained(X));
  const Eigen::Vector2d t(std::cos(c.phi_rad), -std::sin(c.phi_rad));
  only->at_point(e, g, Eigen::Vector2d(c.x_mm, c.y_mm), b0, db0);  // the offset of this point from its own column
  const double w0 = -b0.dot(t) / k_t;  // it sticks there (|w0| < limit / k_t: within the element)
  const Eigen::Vector2d x_slip = Eigen::Vector2d(c.x_mm, c.y_mm) + (3.0 * limit / k_t - w0) * t;  // w = 3 limit / k_t
  only->at_point(e, g, x_slip, b1, db0);
  EXPECT_NEAR(b1.dot(t), -limit, 1e-15);
  EXPECT_EQ(db0.norm(), 0.0);
  const std::vector<Eigen::Vector2d> at_slip(m.element_count() * points, x_slip);  // point (e, g) among them
  only->commit({1.0, nullptr, &at_slip, points});
  only->prepare(1.0);  // the commit takes effect at the next level
  only->at_point(e, g, x_slip, b1, db0);
  EXPECT_NEAR(b1.dot(t), -limit, 1e-15);  // the commit keeps the force
  EXPECT_NEAR(db0.norm(), k_t, 1e-12);    // and now sticks there
  only->at_point(e, g, x_slip - 0.5 * limit / k_t * t, b2, db0);
  EXPECT_NEAR(b2.dot(t), -0.5 * limit, 1e-15);  // elastic unloading from the slipped state
}

TEST(SegmentFlank, BlockPulledAlongTheBeltSticksSlipsAndUnloadsElastically) {
  // Every node's x prescribed to U(λ), a rigid motion along the cord (no stress): the flank's
  // longitudinal force on the block is −k_t U V while k_t U ≤ limit, −limit V while it slips, and
  // from the largest pull U_m back, −limit V + k_t (U_m − U) V (the committed slip).
  const Mesh m = strip();
  const auto law = make_elastic(ElasticLaw::hencky, 10.0, 0.3);
  const double k_t = 0.3, limit = 0.02, U_s = limit / k_t, volume = kHeight_mm * 2.0 * m.half_length_mm;
  StaticProblem p = block_along_the_belt(m, *law, true);
  auto U = [U_s](double lambda) { return lambda <= 0.5 ? 4.0 * U_s * lambda : 2.0 * U_s - 4.0 * U_s * (lambda - 0.5); };
  p.motion = prescribed([&U](double lambda, std::vector<std::array<double, 2>>& v) {
    for (auto& x : v) x = {U(lambda), 0.0};
  });
  const NeutralCurve line = NeutralCurve::uniform(0.0, 0.0, 1.5 * m.half_length_mm);
  p.loads.push_back(stick_contact(m, line, 0.0, k_t, limit));
  std::vector<std::pair<double, double>> pulled;  // λ, Σ reactions along x
  CallbackObserver watch([&](double lambda, const StaticSolution& s) {
    double r = 0.0;
    for (const Eigen::Vector2d& f : s.reaction_N_mm) r += f.x();
    pulled.emplace_back(lambda, r);
  });
  p.observers.push_back(&watch);
  SolverKnobs knobs;
  knobs.stepping.steps = 8;
  solve_static(p, knobs);
  ASSERT_EQ(pulled.size(), 8u);
  for (const auto& [lambda, r] : pulled) {
    const double u = U(lambda);
    const double expected = lambda <= 0.5 ? std::min(k_t * u, limit) * volume : (limit - k_t * (2.0 * U_s - u)) * volume;
    EXPECT_NEAR(r, expected, 1e-12 * limit * volume) << "lambda " << lambda;
  }
  EXPECT_NEAR(pulled.back().second, -limit * volume, 1e-12 * limit * volume);  // unloaded to the opposite slip
}

TEST(SegmentFlank, FreeBlockUnderALoadAlongTheBeltSticksAtLoadOverKtAndHasNoEquilibriumBeyondTheLimit) {
  const Mesh m = strip();
  const auto law = make_elastic(ElasticLaw::hencky, 10.0, 0.3);
  const double k_t = 0.3, limit = 0.02;
  const NeutralCurve line = NeutralCurve::uniform(0.0, 0.0, 1.5 * m.half_length_mm);
  auto run = [&](double load) {
    StaticProblem p = block_along_the_belt(m, *law, false);
    p.motion = prescribed([](double, std::vector<std::array<double, 2>>& v) {
      for (auto& x : v) x = {0.0, 0.0};
    });
    p.loads.push_back(dead_body_force(m.element_count(), [&m, load](double lambda, std::vector<Eigen::Vector2d>& b) {
      b.assign(m.element_count(), Eigen::Vector2d(lambda * load, 0.0));
    }));
    p.loads.push_back(stick_contact(m, line, 0.0, k_t, limit));
    SolverKnobs knobs;
    knobs.stepping.steps = 4;
    return solve_static(p, knobs);
  };
  const double load = 0.8 * limit;
  const StaticSolution s = run(load);
  for (int n = 0; n < m.node_count(); ++n) {
    EXPECT_NEAR(s.u_mm[n].x(), load / k_t, 1e-9 * load / k_t);  // a rigid shift: load / k_t
    EXPECT_NEAR(s.u_mm[n].y(), 0.0, 1e-9 * load / k_t);
  }
  // Linear with its exact tangent: one Newton step per increment beyond the predictor.
  EXPECT_LE(s.newton_iterations, 2 * s.increments);
  EXPECT_THROW(run(1.2 * limit), fitlib::core::NumericalError);  // slides: no static equilibrium
}

TEST(SegmentFlank, SlidingFrictionTurnsWithTheRelativeVelocityAndMatchesCentralDifferences) {
  // Report I's friction −F ê for a few sliding directions γ: unchanged at u̇ = 0, magnitude F kept,
  // ∂b/∂u̇ symmetric and equal to central differences.
  const double F = 0.14, V = 30.0, V0 = 0.03, h = 1e-5;  // V0 ≪ V: Coulomb's direction law
  for (double gamma_deg : {180.0, 205.0, 241.9, 285.7, 354.0, 6.2}) {
    const double g = gamma_deg * M_PI / 180.0;
    const Eigen::Vector2d friction(-F * std::sin(g), -F * std::cos(g));
    EXPECT_EQ(flank_slide_point(Eigen::Vector2d::Zero(), friction, V, V0).b_lr_N_mm3.norm(), 0.0);
    for (const Eigen::Vector2d& u_dot : {Eigen::Vector2d(12.0, 0.0), Eigen::Vector2d(-40.0, 3.0), Eigen::Vector2d(0.5, -7.0)}) {
      const FlankSlidePoint p = flank_slide_point(u_dot, friction, V, V0);
      EXPECT_NEAR((p.b_lr_N_mm3 + friction).norm(), F, 1e-5 * F) << gamma_deg;  // the whole friction: F, turned
      EXPECT_NEAR((p.db_dv_lr - p.db_dv_lr.transpose()).norm(), 0.0, 1e-18);
      for (int j = 0; j < 2; ++j) {
        const Eigen::Vector2d e = Eigen::Vector2d::Unit(j) * h;
        const Eigen::Vector2d fd =
            (flank_slide_point(u_dot + e, friction, V, V0).b_lr_N_mm3 - flank_slide_point(u_dot - e, friction, V, V0).b_lr_N_mm3) /
            (2.0 * h);
        EXPECT_LT((fd - p.db_dv_lr.col(j)).norm(), 1e-9 * F / V) << gamma_deg;
      }
      // Moving along the sliding direction's normal turns the friction against that motion.
      EXPECT_LT(u_dot.dot(p.b_lr_N_mm3), 1e-15);
    }
  }
  EXPECT_EQ(flank_slide_point(Eigen::Vector2d(1.0, 0.0), Eigen::Vector2d::Zero(), V, V0).b_lr_N_mm3.norm(), 0.0);  // no friction
  // As the following force on a curved, strained cord curve, with the radial foundation and the
  // stick: b and ∂b/∂x (unsymmetric) against central differences of the position.
  const Mesh m = strip();
  std::vector<double> path_x;
  for (const Eigen::Vector2d& X : m.X) path_x.push_back(X.x());
  const NeutralCurve curve(3.0, {0.02, 0.035, 0.0}, {0.01, 0.012, 0.02, 0.015}, {0.02, 0.0, 0.03}, {0.01, 0.008, 0.0, 0.02});
  const NeutralCurve line = NeutralCurve::uniform(0.0, 0.0, 1.5 * m.half_length_mm);
  const LoadPtr f = flank_contact(m, path_x, Integration::reduced, line, [curve](double) { return curve; },
                                                  true, true, false, [&](double, FlankLevels& l) {
                                                    l.radial_N_mm4.assign(m.element_count(), 0.05);
                                                    l.stick_N_mm4.assign(m.element_count(), 0.3);
                                                    l.stick_limit_N_mm3.assign(m.element_count(), 0.1);
                                                    l.slide_mm_s.assign(m.element_count(), V);
                                                    l.friction_lr_N_mm3.assign(m.element_count(), Eigen::Vector2d(-0.08, 0.11));
                                                    l.slide_floor_mm_s = 5.0, l.time_s = 0.004;
                                                  });
  EXPECT_FALSE(f->symmetric());
  f->prepare(1.0);
  double asymmetry = 0.0;
  for (int e = 0; e < m.element_count(); e += 5)
    for (int g = 0; g < 4; ++g) {
      double X = 0.0;
      for (int a = 0; a < 4; ++a) X += 0.25 * m.X[m.elements[e][a]].x();
      const CurvePoint c = curve.at(curve.s_from_unstrained(X));
      const Eigen::Vector2d x = Eigen::Vector2d(c.x_mm, c.y_mm) - (0.8 + 0.5 * g) * Eigen::Vector2d(std::sin(c.phi_rad), std::cos(c.phi_rad));
      Eigen::Vector2d b, bp, bm;
      Eigen::Matrix2d db, unused;
      ASSERT_TRUE(f->at_point(e, g, x, b, db));
      for (int j = 0; j < 2; ++j) {
        const Eigen::Vector2d step = Eigen::Vector2d::Unit(j) * 1e-7;
        f->at_point(e, g, x + step, bp, unused), f->at_point(e, g, x - step, bm, unused);
        EXPECT_LT(((bp - bm) / 2e-7 - db.col(j)).norm(), 1e-6 * db.norm()) << "element " << e << " point " << g;
      }
      asymmetry = std::max(asymmetry, (db - db.transpose()).norm() / db.norm());
    }
  EXPECT_GT(asymmetry, 1e-3);  // the friction's turn: radial force from motion along the belt

  // Where the sliding stops (V = V0 ≫ |u̇|) it is a viscous stick: −F u̇ / (√2 V0) across ê.
  const FlankSlidePoint stick = flank_slide_point(Eigen::Vector2d(1e-4, 0.0), Eigen::Vector2d(0.0, -F), 5.0, 5.0);
  EXPECT_NEAR(stick.b_lr_N_mm3.x(), -F * 1e-4 / (std::sqrt(2.0) * 5.0), 1e-12 * F);
}

TEST(SegmentFlank, FrictionTurnedByTheFlanksLayerKeepsCoulombsMagnitudeAndMatchesCentralDifferences) {
  // The return onto Coulomb's circle |f| = F: Report I's friction unchanged without motion, the
  // magnitude kept, ∂b/∂w against central differences, the layer relaxed by the sliding.
  const double F = 0.14, k_t = 0.3, h = 1e-7;
  for (double gamma_deg : {180.0, 205.0, 241.9, 285.7, 354.0, 6.2}) {
    const double g = gamma_deg * M_PI / 180.0;
    const Eigen::Vector2d friction(-F * std::sin(g), -F * std::cos(g));
    EXPECT_EQ(flank_turn_point(0.0, 0.0, friction, k_t, 0.01).b_lr_N_mm3.norm(), 0.0);
    for (double dw : {0.02, -0.15, 0.4})
      for (double layer : {0.0, 0.03, -0.05})
        for (double slide : {0.0, 0.002}) {
          const FlankTurnPoint p = flank_turn_point(dw, layer, friction, k_t, slide);
          const double c = F / (F + k_t * slide);
          EXPECT_NEAR(p.layer_after_N_mm3, c * (layer - k_t * dw), 1e-15);
          EXPECT_NEAR((p.b_lr_N_mm3 + friction).norm(), F, 1e-14) << gamma_deg;  // Coulomb's magnitude, turned
          const Eigen::Vector2d fd = (flank_turn_point(dw + h, layer, friction, k_t, slide).b_lr_N_mm3 -
                                      flank_turn_point(dw - h, layer, friction, k_t, slide).b_lr_N_mm3) /
                                     (2.0 * h);
          EXPECT_LT((fd - p.db_dw_lr_N_mm4).norm(), 1e-7 * k_t) << gamma_deg << " " << dw << " " << layer;
        }
  }
  // Radial sliding (γ = 180°): a small motion along the belt meets the stick's k_t (times c) — the
  // friction turns against it, to first order Report I's radial part unchanged.
  const Eigen::Vector2d radial(0.0, F);
  const FlankTurnPoint small = flank_turn_point(1e-5, 0.0, radial, k_t, 0.0);
  EXPECT_NEAR(small.b_lr_N_mm3.x(), -k_t * 1e-5, 1e-12 * k_t);
  EXPECT_NEAR(small.db_dw_lr_N_mm4.x(), -k_t, 1e-6 * k_t);
  // Sliding along the belt (γ = 90°): motion along it changes nothing while the friction keeps its
  // direction (Coulomb: the slip goes on), either way.
  const Eigen::Vector2d along(-F, 0.0);
  EXPECT_EQ(flank_turn_point(0.2, 0.0, along, k_t, 0.0).b_lr_N_mm3.norm(), 0.0);
  EXPECT_EQ(flank_turn_point(-0.2, 0.0, along, k_t, 0.0).b_lr_N_mm3.norm(), 0.0);
  // A rigid-plastic limit: a stiff layer (k_t V Δt ≫ F) turns the friction by the velocity ratio
  // u̇/V, as the sliding friction's direction law does for u̇ ≪ V (flank_slide_point, V0 → 0).
  const double V = 30.0, dt = 1e-3, u_dot = 0.03, stiff = 1e5;
  const FlankTurnPoint rigid = flank_turn_point(u_dot * dt, 0.0, radial, stiff, V * dt);
  const FlankSlidePoint rate = flank_slide_point(Eigen::Vector2d(u_dot, 0.0), radial, V, 1e-9);
  EXPECT_NEAR(rigid.b_lr_N_mm3.x(), rate.b_lr_N_mm3.x(), 1e-4 * std::abs(rate.b_lr_N_mm3.x()));
  EXPECT_NEAR(rigid.b_lr_N_mm3.x(), -F * u_dot / V, 1e-3 * F * u_dot / V);
  // No friction, or no layer: Report I's alone.
  EXPECT_EQ(flank_turn_point(0.2, 0.1, Eigen::Vector2d::Zero(), k_t, 0.0).b_lr_N_mm3.norm(), 0.0);
  EXPECT_EQ(flank_turn_point(0.2, 0.1, radial, 0.0, 0.0).b_lr_N_mm3.norm(), 0.0);
}

TEST(SegmentFlank, BlockUnderALoadAlongTheBeltCreepsAtTheCoulombVelocity) {
  // A block in radial sliding (γ = 0, speed V; Report I's friction −F radially and none along the
  // belt), held radially, under a load b0 along the belt: the friction turns until its component
  // along the belt balances b0, F u̇ / √(u̇² + V²) = b0, so the block creeps at
  // u̇ = V b0 / √(F² − b0²), u = u̇ t, with the time step's size irrelevant (backward Euler of a
  // constant velocity); beyond b0 = F it has no equilibrium. (With the regularisation V0 the
  // speed is √(V² + V0²) in place of V.)
  const Mesh m = strip();
  const auto law = make_elastic(ElasticLaw::hencky, 10.0, 0.3);
  const double F = 0.02, V = 25.0, V0 = 5.0, duration = 0.01;
  std::vector<double> path_x;
  for (const Eigen::Vector2d& X : m.X) path_x.push_back(X.x());
  const NeutralCurve line = NeutralCurve::uniform(0.0, 0.0, 1.5 * m.half_length_mm);
  auto run = [&](double load, int steps) {
    StaticProblem p;
    p.mesh = &m;
    p.laws = {law.get(), law.get()};
    for (int n = 0; n < m.node_count(); ++n) p.constraints.push_back({n, 0.0, {false, true}});
    p.motion = prescribed([](double, std::vector<std::array<double, 2>>& v) {
      for (auto& x : v) x = {0.0, 0.0};
    });
    p.time_s = [duration](double lambda) { return lambda * duration; };
    p.loads.push_back(dead_body_force(m.element_count(), [&m, load](double, std::vector<Eigen::Vector2d>& b) { b.assign(m.element_count(), Eigen::Vector2d(load, 0.0)); }));
    p.loads.push_back(flank_contact(m, path_x, Integration::reduced, line, [line](double) { return line; }, false, true, false,
                                      [&](double lambda, FlankLevels& l) {
                                        for (auto* v : {&l.radial_N_mm4, &l.stick_N_mm4, &l.stick_limit_N_mm3}) v->assign(m.element_count(), 0.0);
                                        l.slide_mm_s.assign(m.element_count(), V);
                                        l.friction_lr_N_mm3.assign(m.element_count(), Eigen::Vector2d(0.0, -F));
                                        l.time_s = lambda * duration, l.slide_floor_mm_s = V0;
                                      }));
    SolverKnobs knobs;
    knobs.stepping.steps = steps;
    return solve_static(p, knobs);
  };
  const double load = 0.6 * F, creep = std::hypot(V, V0) * load / std::sqrt(F * F - load * load);
  for (int steps : {1, 5}) {
    const StaticSolution s = run(load, steps);
    for (int n = 0; n < m.node_count(); ++n) EXPECT_NEAR(s.u_mm[n].x(), creep * duration, 1e-6 * creep * duration) << steps;  // Newton's tolerance
    // The friction's radial part: −F V / |v| (Report I's −F less the turn).
    Eigen::Vector2d total = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& f : s.following_N_mm) total += f;
    const double volume = kHeight_mm * 2.0 * m.half_length_mm, q = std::sqrt(creep * creep + V * V + V0 * V0);
    EXPECT_NEAR(total.x(), -F * creep / q * volume, 1e-6 * F * volume);
    EXPECT_NEAR(total.y(), (-F * V / q + F * V / std::hypot(V, V0)) * volume, 1e-6 * F * volume);
  }
  EXPECT_THROW(run(1.05 * F, 2), fitlib::core::NumericalError);
}

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
  p.motion = prescribed([delta](double lambda, std::vector<std::array<double, 2>>& v) {
    for (auto& x : v) x = {0.0, -lambda * delta};
  });
  p.loads.push_back(straight_foundation(m, k));
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
  p.loads.push_back(dead_body_force(m.element_count(), [&m, b0](double lambda, std::vector<Eigen::Vector2d>& b) {
    b.assign(m.element_count(), Eigen::Vector2d(0.0, lambda * b0));
  }));
  p.loads.push_back(straight_foundation(m, k));
  SolverKnobs knobs;
  knobs.stepping.steps = 2;
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
