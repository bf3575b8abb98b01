// The segment driven by a load cycle (Report I §5–§6, belt-mechanics.md §5): the qualitative
// features on a synthetic one-pulley cycle of known shape, periodicity of an elastic belt,
// equilibrium, and the failure exit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <unistd.h>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/segment/cycle.hpp"
#include "fitlib/segment/point_law.hpp"

using namespace fitlib;
using namespace fitlib::segment;

namespace {

// 400 mm belt at 1000 mm/s: span (0–90), entrance ramp of K (90–100), wrap of R = 40 mm
// (100–200) with side pressure, the last 40 mm sliding (γ = 0.4, force rising), exit ramp
// (200–210), span. F 300 N in the slack span, 600 N after the sliding zone; friction used μ throughout
// (no driver-exit ramp; it only acts where p > 0).
belt::LoadCycle synthetic_cycle(double pressure_MPa = 0.4, double radius_mm = 40.0, double friction = 0.8) {
  belt::LoadCycle c;
  c.cycle_length_mm = 400.0;
  c.cycle_time_s = 0.4;
  struct P { double s, F, K, p, g; };
  const double K = 1.0 / radius_mm;
  const P pts[] = {{0, 300, 0, 0, 0},       {90, 300, 0, 0, 0},          {100, 300, K, pressure_MPa, 0},
                   {160, 300, K, pressure_MPa, 0}, {160.001, 300, K, pressure_MPa, 0.4},
                   {200, 600, K, 2 * pressure_MPa, 0.4}, {210, 600, 0, 0, 0}, {310, 600, 0, 0, 0},
                   {390, 300, 0, 0, 0}};
  for (const P& q : pts) {
    belt::LoadSample s;
    s.s_mm = q.s, s.t_s = q.s / 1000.0, s.F_N = q.F, s.K_1_mm = q.K, s.p_MPa = q.p, s.gamma_rad = q.g;
    s.friction_used = friction;
    c.samples.push_back(s);
  }
  return c;
}

struct Fixture {
  belt::LoadHistory history;
  CycleDrive drive;
  MeshKnobs mesh;
  SolverKnobs solver;
  CycleKnobs knobs;
  explicit Fixture(const belt::LoadCycle& cycle = synthetic_cycle())
      : history(cycle, [] { belt::BeltSection b; b.c_N = 44000.0; return b; }(), 20.0) {
    drive.history = &history;
    drive.wedge_half_angle_rad = 19.0 * M_PI / 180.0;
    drive.speed_mm_s = 1000.0;
    mesh.fine_size_mm = 1.0, mesh.coarse_size_mm = 2.5, mesh.central_pitches = 1.0, mesh.end_pitches = 1.0;
    mesh.cushion_rows = 1;
    knobs.stepping.cycles = 2;
    knobs.stepping.steps_per_cycle = 24;
    knobs.physics.manufactured_radius_mm = 0.0;
  }
  CycleResult run(const PlaneStrainLaw& bottom, const PlaneStrainLaw& cushion) const {
    return run_cycle(CogSection{}, mesh, solver, {&bottom, &cushion}, drive, knobs);
  }
};

std::unique_ptr<PlaneStrainLaw> hencky(double E, double nu) { return make_elastic(ElasticLaw::hencky, E, nu); }

const MonitoredHistory& point(const CycleResult& r, const std::string& name) {
  for (const auto& p : r.points)
    if (p.point.name == name) return p;
  throw std::runtime_error("no point " + name);
}

// The sample of cycle `c` (1-based) nearest path position s of the segment's middle.
const CycleSample& at(const MonitoredHistory& h, int c, double s, double L = 400.0) {
  const CycleSample* best = &h.samples.front();
  for (const auto& q : h.samples)
    if (std::abs(q.s_mm - ((c - 1) * L + s)) < std::abs(best->s_mm - ((c - 1) * L + s))) best = &q;
  return *best;
}

// The point law with history these tests run: a two-term shear Prony with a bulk modulus.
const ContractLaw& prony_point() {
  static const model::ModelPtr prony = model::make_model("prony", {{"mode", "shear"}, {"bulk_modulus", true}, {"terms", 2}});
  static const ContractLaw law(model::make_material_point(*prony, {2.0, 3.0, 2.0, 0.05, 0.5, 2000.0}));
  return law;
}

// One cycle of the Prony point on the default fixture, with the Newton options `set` changes.
CycleResult prony_cycle(const std::function<void(NewtonOptions&)>& set) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  set(f.solver.newton);
  return f.run(prony_point(), prony_point());
}

// Every monitored stress of `r` equal to `ref`'s within `tolerance` × (1 + |σ22| + |σ11|) MPa.
void expect_same_stresses(const CycleResult& r, const CycleResult& ref, double tolerance) {
  for (std::size_t p = 0; p < ref.points.size(); ++p)
    for (std::size_t q = 0; q < ref.points[p].samples.size(); ++q) {
      const CycleSample &a = r.points[p].samples[q], &b = ref.points[p].samples[q];
      const double scale = tolerance * (1.0 + std::abs(b.s22_MPa) + std::abs(b.s11_MPa));
      ASSERT_NEAR(a.s11_MPa, b.s11_MPa, scale) << ref.points[p].point.name << " " << q;
      ASSERT_NEAR(a.s22_MPa, b.s22_MPa, scale) << ref.points[p].point.name << " " << q;
      ASSERT_NEAR(a.s12_MPa, b.s12_MPa, scale) << ref.points[p].point.name << " " << q;
    }
}

}  // namespace

TEST(SegmentCycle, ElasticBeltFollowsTheCycleInEquilibriumAndRepeatsItself) {
  Fixture f;
  f.knobs.stepping.repeat_history_free_cycle = false;  // both cycles solved: the repetition is the physics'
  std::vector<double> progress;  // the share of the run done, after each converged increment
  f.knobs.outputs.progress = [&](double done) { progress.push_back(done); };
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult r = f.run(*bottom, *cushion);
  ASSERT_EQ(static_cast<int>(progress.size()), r.increments);
  EXPECT_TRUE(std::is_sorted(progress.begin(), progress.end()));
  EXPECT_GT(progress.front(), 0.0);
  EXPECT_DOUBLE_EQ(progress.back(), 1.0);
  const MonitoredHistory& gap = point(r, "gap_bottom");
  EXPECT_LT(r.equilibrium_error, 1e-6);
  // Tension between the cogs in the spans (cord strain ≈ 0.7 %), compression on the pulley.
  EXPECT_GT(at(gap, 2, 50.0).s22_MPa, 0.0);
  EXPECT_LT(at(gap, 2, 140.0).s22_MPa, 0.0);
  // An elastic belt repeats: cycle 2 equals cycle 1 at the same path position.
  for (double s : {50.0, 140.0, 190.0, 300.0})
    EXPECT_NEAR(at(gap, 2, s).s22_MPa, at(gap, 1, s).s22_MPa, 1e-6 * (1.0 + std::abs(at(gap, 1, s).s22_MPa))) << s;
  std::printf("equilibrium error %.3g; ", r.equilibrium_error);
  std::printf("gap s22: span %.4f, arc %.4f, sliding %.4f MPa; %d increments, %d iterations\n",
              at(gap, 2, 50.0).s22_MPa, at(gap, 2, 140.0).s22_MPa, at(gap, 2, 190.0).s22_MPa, r.increments,
              r.newton_iterations);
  for (const auto& p : r.points)
    for (const auto& q : p.samples) ASSERT_TRUE(std::isfinite(q.s11_MPa + q.s22_MPa + q.s12_MPa + q.e22));
}

TEST(SegmentCycle, StraighteningTheMouldedCurvatureStressesTheBelt) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  f.knobs.stepping.steps_per_cycle = 4;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const double straight = point(f.run(*bottom, *cushion), "gap_bottom").samples[f.knobs.stepping.bend_steps - 1].s22_MPa;
  f.knobs.physics.manufactured_radius_mm = 40.0;
  const double moulded = point(f.run(*bottom, *cushion), "gap_bottom").samples[f.knobs.stepping.bend_steps - 1].s22_MPa;
  // Straightening opens the inside of the mould: extra tension at the gap bottom.
  EXPECT_GT(moulded - straight, 0.2);
  std::printf("gap s22 after step 1: straight mould %.4f, R 40 mm mould %.4f MPa\n", straight, moulded);
}

TEST(SegmentCycle, FrictionChangesTheShearInTheSlidingZone) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult with = f.run(*bottom, *cushion);
  Fixture frictionless(synthetic_cycle(0.4, 40.0, 0.0));  // the load cycle's friction used is the segment's
  frictionless.knobs = f.knobs;
  const CycleResult without = frictionless.run(*bottom, *cushion);
  const double d_sliding = at(point(with, "mid_cushion"), 1, 190.0).s12_MPa - at(point(without, "mid_cushion"), 1, 190.0).s12_MPa;
  const double d_sticking = at(point(with, "mid_cushion"), 1, 130.0).s12_MPa - at(point(without, "mid_cushion"), 1, 130.0).s12_MPa;
  EXPECT_GT(std::abs(d_sliding), 10.0 * std::abs(d_sticking));
  std::printf("mid-cushion s12 change by friction: sliding %.4g, non-sliding %.4g MPa\n", d_sliding, d_sticking);
}

TEST(SegmentCycle, ViscoelasticBeltDiffersBetweenCycleOneAndTwo) {
  Fixture f;
  const ContractLaw& law = prony_point();
  const CycleResult r = f.run(law, law);
  const MonitoredHistory& gap = point(r, "gap_bottom");
  double largest = 0.0;
  for (double s : {50.0, 140.0, 300.0}) largest = std::max(largest, std::abs(at(gap, 2, s).s22_MPa - at(gap, 1, s).s22_MPa));
  EXPECT_GT(largest, 1e-3);
  std::printf("viscoelastic gap s22 cycle 2 − cycle 1: largest %.4g MPa\n", largest);
}

// The element loop on 1, 2 and 3 threads (SolverKnobs::threads): the same increments, iterations
// and cuts, and every monitored stress, displacement and point state equal to the last bit — for a
// point law with history (UMFPACK's LU, states carried between increments) and an elastic one (LDLᵀ).
TEST(SegmentCycle, ThreadCountLeavesEveryResultBitIdentical) {
  const ContractLaw& visco = prony_point();
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  for (const bool history : {true, false}) {
    std::vector<CycleResult> runs;
    for (const int threads : {1, 2, 3}) {
      Fixture f;
      f.knobs.stepping.cycles = history ? 2 : 1;
      f.solver.threads = threads;
      runs.push_back(history ? f.run(visco, visco) : f.run(*bottom, *cushion));
      EXPECT_EQ(runs.back().final_state.threads, threads);
    }
    const CycleResult& one = runs.front();
    EXPECT_EQ(one.final_state.symmetric_solver, !history);
    for (std::size_t k = 1; k < runs.size(); ++k) {
      const CycleResult& r = runs[k];
      EXPECT_EQ(r.increments, one.increments);
      EXPECT_EQ(r.newton_iterations, one.newton_iterations);
      EXPECT_EQ(r.cuts, one.cuts);
      EXPECT_EQ(r.final_state.state, one.final_state.state);  // exact: operator== on the doubles
      ASSERT_EQ(r.final_state.u_mm.size(), one.final_state.u_mm.size());
      for (std::size_t n = 0; n < one.final_state.u_mm.size(); ++n)
        ASSERT_EQ(r.final_state.u_mm[n], one.final_state.u_mm[n]) << "node " << n;
      ASSERT_EQ(r.points.size(), one.points.size());
      for (std::size_t p = 0; p < one.points.size(); ++p) {
        ASSERT_EQ(r.points[p].samples.size(), one.points[p].samples.size());
        for (std::size_t q = 0; q < one.points[p].samples.size(); ++q) {
          const CycleSample &a = r.points[p].samples[q], &b = one.points[p].samples[q];
          ASSERT_TRUE(a.s11_MPa == b.s11_MPa && a.s22_MPa == b.s22_MPa && a.s12_MPa == b.s12_MPa &&
                      a.s33_MPa == b.s33_MPa && a.e22 == b.e22)
              << one.points[p].point.name << " sample " << q << " with " << k + 1 << " threads";
        }
      }
    }
    std::printf("%s: %d increments, %d iterations on 1, 2 and 3 threads, bit-identical\n",
                history ? "prony (LU)" : "hencky (LDLT)", one.increments, one.newton_iterations);
  }
}

// An unsymmetric tangent (a Prony point) solved by GMRES on its symmetric part's LDLᵀ (the default)
// takes Newton through the same increments and iterations as UMFPACK's LU every time
// (krylov_iterations = 0), to stresses equal within 10⁻⁸ of their scale; a GMRES allowed one
// iteration at an unreachable tolerance falls back to the LU on every tangent, with the LU's result;
// modified Newton (reuse_tangent) factorises with the LU as before.
TEST(SegmentCycle, UnsymmetricTangentByGmresOnItsSymmetricPartKeepsNewtonsIterations) {
  auto run = [](int iterations, double tolerance) {
    return prony_cycle([&](NewtonOptions& n) { n.krylov_iterations = iterations, n.krylov_tolerance = tolerance; });
  };
  const CycleResult lu = run(0, 1e-8), gmres = run(SolverKnobs{}.newton.krylov_iterations, SolverKnobs{}.newton.krylov_tolerance),
                    fallback = run(1, 1e-300);
  EXPECT_FALSE(gmres.final_state.symmetric_solver);
  EXPECT_EQ(lu.final_state.krylov_iterations, 0);
  EXPECT_GT(gmres.final_state.krylov_iterations, gmres.factorizations);  // it iterated, on every tangent
  EXPECT_EQ(gmres.final_state.krylov_fallbacks, 0);
  EXPECT_EQ(fallback.final_state.krylov_fallbacks, fallback.factorizations);
  for (const CycleResult* r : {&gmres, &fallback}) {
    EXPECT_EQ(r->increments, lu.increments);
    EXPECT_EQ(r->newton_iterations, lu.newton_iterations);
    EXPECT_EQ(r->cuts, lu.cuts);
    expect_same_stresses(*r, lu, 1e-8);
  }
  // Modified Newton keeps the LU for its later steps: no GMRES there, and the same solution.
  const CycleResult reused = prony_cycle([](NewtonOptions& n) { n.reuse_tangent = true; });
  EXPECT_EQ(reused.final_state.krylov_iterations, 0);
  const CycleSample &a = point(reused, "gap_bottom").samples.back(), &b = point(lu, "gap_bottom").samples.back();
  EXPECT_NEAR(a.s22_MPa, b.s22_MPa, 1e-6 * (1.0 + std::abs(b.s22_MPa)));
  std::printf("prony cycle: %d factorisations, %d GMRES iterations (%.2f per factorisation), %d Newton iterations either way\n",
              gmres.factorizations, gmres.final_state.krylov_iterations,
              double(gmres.final_state.krylov_iterations) / gmres.factorizations, gmres.newton_iterations);
}

// GMRES near convergence on the preconditioner of an earlier iterate (the default
// keep_preconditioner_below) takes Newton through the same increments and iterations as a
// factorisation per tangent, to stresses equal within 10⁻⁸ of their scale, with fewer factorisations.
TEST(SegmentCycle, NearConvergenceGmresKeepsTheLastPreconditionerAndNewtonsIterations) {
  auto run = [](double keep_below) { return prony_cycle([&](NewtonOptions& n) { n.keep_preconditioner_below = keep_below; }); };
  const CycleResult fresh = run(0.0), kept = run(SolverKnobs{}.newton.keep_preconditioner_below);
  EXPECT_EQ(fresh.factorizations, fresh.newton_iterations);
  EXPECT_LT(kept.factorizations, fresh.factorizations);
  EXPECT_EQ(kept.final_state.krylov_fallbacks, 0);
  EXPECT_EQ(kept.increments, fresh.increments);
  EXPECT_EQ(kept.newton_iterations, fresh.newton_iterations);
  EXPECT_EQ(kept.cuts, fresh.cuts);
  expect_same_stresses(kept, fresh, 1e-8);
  std::printf("prony cycle: %d Newton iterations either way; %d factorisations and %d GMRES iterations kept, %d and %d fresh\n",
              kept.newton_iterations, kept.factorizations, kept.final_state.krylov_iterations, fresh.factorizations,
              fresh.final_state.krylov_iterations);
}

// The LDLᵀ in two halves at once (split_factorisation, on by default) changes the rounding of each
// solve, not Newton's path: the same increments, iterations, factorisations and cuts as one LDLᵀ,
// the stresses to round-off.
TEST(SegmentCycle, SplitFactorisationKeepsNewtonsPathAndTheStresses) {
  auto run = [](bool split) { return prony_cycle([&](NewtonOptions& n) { n.split_factorisation = split; }); };
  const CycleResult one = run(false), split = run(true);
  EXPECT_FALSE(one.final_state.split_factorisation);
  EXPECT_TRUE(split.final_state.split_factorisation);
  EXPECT_EQ(split.increments, one.increments);
  EXPECT_EQ(split.newton_iterations, one.newton_iterations);
  EXPECT_EQ(split.factorizations, one.factorizations);
  EXPECT_EQ(split.cuts, one.cuts);
  expect_same_stresses(split, one, 1e-9);
}

// Cycles before the last at their own, coarser count (conditioning_steps): the bend, that many
// increments in each, then the full count in the last, the one a life reads, sampled at the same
// path positions, its stresses moved only through the points' memory (a Prony point relaxing over
// the cycle: within 1 % of the largest stress).
TEST(SegmentCycle, CoarserConditioningCyclesOnlyBringTheMemoryToTheCycleTheLifeReads) {
  const ContractLaw& visco = prony_point();
  auto run = [&](int first) {
    Fixture f;
    f.knobs.stepping.cycles = 3;
    f.knobs.stepping.conditioning_steps = first;
    EXPECT_EQ(planned_increments(f.knobs.stepping), 4 + 2 * (first > 0 ? first : 24) + 24);
    return f.run(visco, visco);
  };
  const CycleResult full = run(0), coarse = run(12);
  EXPECT_EQ(full.increments - coarse.increments, 24);
  EXPECT_EQ(full.cuts + coarse.cuts, 0);
  double largest = 0.0, moved = 0.0;
  for (const char* name : {"gap_bottom", "mid_cushion"}) {
    const MonitoredHistory &a = point(full, name), &b = point(coarse, name);
    const std::size_t last = 24;  // the last cycle's samples, one per increment
    ASSERT_GE(a.samples.size(), last);
    ASSERT_GE(b.samples.size(), last);
    for (std::size_t k = 1; k <= last; ++k) {
      const CycleSample &p = a.samples[a.samples.size() - k], &q = b.samples[b.samples.size() - k];
      ASSERT_DOUBLE_EQ(p.s_mm, q.s_mm) << name << " " << k;
      largest = std::max({largest, std::abs(p.s11_MPa), std::abs(p.s22_MPa), std::abs(p.s12_MPa)});
      moved = std::max({moved, std::abs(p.s11_MPa - q.s11_MPa), std::abs(p.s22_MPa - q.s22_MPa), std::abs(p.s12_MPa - q.s12_MPa)});
    }
  }
  EXPECT_GT(moved, 0.0);  // the memory differs: the cycles before did run coarser
  EXPECT_LT(moved, 1e-2 * largest);
  std::printf("prony cycle, two cycles of 12 against 24 steps before the last: its stresses moved %.3g MPa of %.3g MPa\n", moved, largest);
}

TEST(SegmentCycle, ImpossibleCurvatureExitsNamingTheIncrement) {
  Fixture f(synthetic_cycle());
  f.knobs.stepping.cycles = 1;
  f.knobs.physics.manufactured_radius_mm = 0.8;  // tighter than the section is high: elements invert
  f.solver.stepping.max_cuts = 2;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  try {
    f.run(*bottom, *cushion);
    FAIL() << "expected a numerical failure";
  } catch (const core::NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("load increment"), std::string::npos) << what;
    EXPECT_NE(what.find("element"), std::string::npos) << what;
    std::printf("%s\n", what.c_str());
  }
}

TEST(SegmentCycle, WritesTheStressFieldAtChosenInstantsAndTheHistoriesWithoutNaN) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  f.knobs.stepping.steps_per_cycle = 12;
  const std::string dir = ::testing::TempDir() + "/segment-cycle-" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  f.knobs.outputs.vtk_prefix = dir + "/field";
  f.knobs.outputs.vtk_at_s_mm = {95.0, 205.0};  // entrance and exit transitions
  const auto law = hencky(20.0, 0.49);
  const CycleResult r = f.run(*law, *law);
  ASSERT_EQ(r.vtk_files.size(), 2u);
  for (const auto& path : r.vtk_files) {
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("CELLS"), std::string::npos);
    EXPECT_EQ(text.find("nan"), std::string::npos);
  }
  write_cycle_csv(r, dir + "/cycle.csv");
  std::ifstream csv(dir + "/cycle.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.rfind("point,role,x_mm,y_mm,t_s,s_mm,s11_MPa", 0), 0u);
  EXPECT_EQ(text.find("nan"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(SegmentCycle, NearIncompressibleBeltRunsTheCycle) {
  // K/G = 1000: the step cuts do the work; stresses stay finite and close to ν = 0.49's.
  Fixture f;
  f.knobs.stepping.cycles = 1;
  f.knobs.stepping.steps_per_cycle = 12;
  const auto b49 = hencky(20.0, 0.49), c49 = hencky(8.0, 0.49);
  const auto b4995 = hencky(20.0, 0.4995), c4995 = hencky(8.0, 0.4995);
  const CycleResult soft = f.run(*b49, *c49), hard = f.run(*b4995, *c4995);
  const double a = at(point(soft, "gap_bottom"), 1, 140.0).s22_MPa, b = at(point(hard, "gap_bottom"), 1, 140.0).s22_MPa;
  EXPECT_TRUE(std::isfinite(b));
  EXPECT_NEAR(b, a, 0.2 * std::abs(a));
  EXPECT_LT(hard.equilibrium_error, 1e-6);
  std::printf("gap s22 on the pulley: nu 0.49 %.4f, nu 0.4995 %.4f MPa (%d vs %d increments)\n", a, b,
              soft.increments, hard.increments);
}

// The solver factors with LDLᵀ when every law's tangent is symmetric (an isotropic elastic contract
// point) and with LU otherwise; both give the same cycle, and the sparsity pattern is analysed
// once per run, not per increment.
namespace {
struct SaysUnsymmetric final : PlaneStrainLaw {  // the same law, declared unsymmetric
  explicit SaysUnsymmetric(const PlaneStrainLaw& law) : law_(law) {}
  bool symmetric_tangent() const override { return false; }
  using PlaneStrainLaw::respond;
  PointResponse respond(const Matrix2& F, const PointStep& step) const override { return law_.respond(F, step); }
  const PlaneStrainLaw& law_;
};
}  // namespace

TEST(SegmentCycle, SymmetricSolverAgreesWithLuAndAnalysesThePatternOnce) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult ldlt = f.run(*bottom, *cushion);
  const CycleResult lu = f.run(SaysUnsymmetric(*bottom), SaysUnsymmetric(*cushion));
  EXPECT_TRUE(ldlt.final_state.symmetric_solver);
  EXPECT_FALSE(lu.final_state.symmetric_solver);
  for (const CycleResult* r : {&ldlt, &lu}) {
    EXPECT_EQ(r->final_state.pattern_analyses, 1);
    EXPECT_GT(r->factorizations, r->increments);
  }
  ASSERT_EQ(ldlt.points[0].samples.size(), lu.points[0].samples.size());
  double diff = 0.0, size = 0.0;
  for (std::size_t k = 0; k < ldlt.points[0].samples.size(); ++k) {
    diff = std::max(diff, std::abs(ldlt.points[0].samples[k].s22_MPa - lu.points[0].samples[k].s22_MPa));
    size = std::max(size, std::abs(lu.points[0].samples[k].s22_MPa));
  }
  EXPECT_LT(diff, 1e-7 * size);
}

// A history-free run solves the bend and one cycle and copies it to the later cycles
// (CycleStepping::repeat_history_free_cycle): against every cycle solved, the same samples' times and
// path positions, stresses to the Newton tolerance, the same load totals, and half the increments.
TEST(SegmentCycle, AHistoryFreeRunsCopiedCyclesEqualTheSolvedOnes) {
  Fixture f;
  f.knobs.stepping.cycles = 3;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult copied = f.run(*bottom, *cushion);
  f.knobs.stepping.repeat_history_free_cycle = false;
  const CycleResult solved = f.run(*bottom, *cushion);
  EXPECT_LT(copied.increments, 0.5 * solved.increments);
  ASSERT_EQ(copied.loads.size(), solved.loads.size());
  for (std::size_t i = 0; i < solved.loads.size(); ++i) {
    EXPECT_NEAR(copied.loads[i].s_mm, solved.loads[i].s_mm, 1e-9) << i;
    EXPECT_NEAR(copied.loads[i].belt_force_N_mm, solved.loads[i].belt_force_N_mm, 1e-9) << i;
  }
  ASSERT_EQ(copied.points.size(), solved.points.size());
  for (std::size_t k = 0; k < solved.points.size(); ++k) {
    const auto &a = copied.points[k].samples, &b = solved.points[k].samples;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < b.size(); ++i) {
      EXPECT_NEAR(a[i].t_s, b[i].t_s, 1e-12) << i;
      EXPECT_NEAR(a[i].s22_MPa, b[i].s22_MPa, 1e-7 * (1.0 + std::abs(b[i].s22_MPa))) << i;
      EXPECT_NEAR(a[i].s11_MPa, b[i].s11_MPa, 1e-7 * (1.0 + std::abs(b[i].s11_MPa))) << i;
    }
  }
  EXPECT_NEAR(copied.equilibrium_error, solved.equilibrium_error, 1e-9);
}

// The one cycle of a history-free run solved as two halves at once (CycleStepping::
// split_history_free_cycle; segment/cycle_split.hpp): the second half starts from its own bend to the
// state at a planned increment in the span after the pulley. Against the cycle in one piece: the same
// samples (times and path positions), stresses and load totals to the Newton tolerance, the counts
// one bend more; on one thread or two, the same bytes.
TEST(SegmentCycle, AHistoryFreeCycleInTwoHalvesEqualsTheCycleInOnePiece) {
  Fixture f;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult halves = f.run(*bottom, *cushion);
  f.solver.threads = 1;
  const CycleResult serial = f.run(*bottom, *cushion);
  f.knobs.stepping.split_history_free_cycle = false;
  const CycleResult whole = f.run(*bottom, *cushion);
  EXPECT_EQ(halves.increments, whole.increments + f.knobs.stepping.bend_steps);
  ASSERT_EQ(halves.loads.size(), whole.loads.size());
  for (std::size_t i = 0; i < whole.loads.size(); ++i) {
    EXPECT_NEAR(halves.loads[i].s_mm, whole.loads[i].s_mm, 1e-9) << i;
    EXPECT_NEAR(halves.loads[i].t_s, whole.loads[i].t_s, 1e-12) << i;
    EXPECT_NEAR((halves.loads[i].cord_reaction_N_mm - whole.loads[i].cord_reaction_N_mm).norm(), 0.0, 1e-7) << i;
  }
  ASSERT_EQ(halves.points.size(), whole.points.size());
  for (std::size_t k = 0; k < whole.points.size(); ++k) {
    const auto &a = halves.points[k].samples, &b = whole.points[k].samples, &c = serial.points[k].samples;
    ASSERT_EQ(a.size(), b.size());
    ASSERT_EQ(c.size(), b.size());
    for (std::size_t i = 0; i < b.size(); ++i) {
      EXPECT_NEAR(a[i].t_s, b[i].t_s, 1e-12) << i;
      EXPECT_NEAR(a[i].s_mm, b[i].s_mm, 1e-9) << i;
      for (auto m : {&CycleSample::s11_MPa, &CycleSample::s22_MPa, &CycleSample::s12_MPa})
        EXPECT_NEAR(a[i].*m, b[i].*m, 1e-7 * (1.0 + std::abs(b[i].*m))) << k << " " << i;
      EXPECT_EQ(a[i].s22_MPa, c[i].s22_MPa) << i;
      EXPECT_EQ(a[i].s12_MPa, c[i].s12_MPa) << i;
    }
  }
  EXPECT_LE(halves.equilibrium_error, 1e-6);
}

TEST(SegmentCycle, ZeroSpeedIsRefusedWithAReason) {
  Fixture f;
  f.drive.speed_mm_s = 0.0;
  const auto law = hencky(20.0, 0.49);
  EXPECT_THROW(f.run(*law, *law), core::InputError);
}

// The built-in equilibrium check during the run: at every increment Σ reactions + ∫ b dV = 0 to the
// Newton tolerance, and the loads are recorded per increment. On the pulley the cord line pushes
// against the contact load (Σ cord reactions · ∫ b dV < 0); it takes only part of it, the rest goes
// to the end faces (measured: docs/segment.md "Validation").
TEST(SegmentCycle, CordLineReactionsAndContactLoadInEquilibriumAtEveryIncrement) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult r = f.run(*bottom, *cushion);
  EXPECT_LT(r.equilibrium_error, 1e-6);
  ASSERT_EQ(r.loads.size(), static_cast<std::size_t>(r.increments));
  int checked = 0;
  double share = 1.0;
  for (const IncrementLoads& q : r.loads) {
    if (q.s_mm < 125.0 || q.s_mm > 175.0) continue;
    ASSERT_GT(q.body_force_N_mm.norm(), 0.0);
    EXPECT_LT(q.cord_reaction_N_mm.dot(q.body_force_N_mm), 0.0) << q.s_mm;
    share = std::min(share, -q.cord_reaction_N_mm.dot(q.body_force_N_mm) / q.body_force_N_mm.squaredNorm());
    ++checked;
  }
  EXPECT_GE(checked, 2);
  std::printf("on the pulley the cord line takes >= %.3g of the contact load (%d increments)\n", share, checked);
}

// Pure bending (no side pressure). Very small curvature (R 4 m) stays in the linear range: the gap
// bottom's σ22 change from span to pulley scales with K (1 % of R 40 mm's, within 15 % for the
// nonlinearity at R 40 mm, 10 % strain at the gap); a very large one (R 20 mm, −30 % at the cog
// tip) still runs, in equilibrium, with a larger change than R 40 mm's.
TEST(SegmentCycle, SmallCurvatureIsLinearAndLargeCurvatureRuns) {
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  auto swing = [&](double radius_mm, double* equilibrium) {
    Fixture f(synthetic_cycle(0.0, radius_mm));
    f.knobs.stepping.cycles = 1;
    f.knobs.stepping.steps_per_cycle = 16;
    const CycleResult r = f.run(*bottom, *cushion);
    *equilibrium = r.equilibrium_error;
    const MonitoredHistory& gap = point(r, "gap_bottom");
    return at(gap, 1, 140.0).s22_MPa - at(gap, 1, 50.0).s22_MPa;
  };
  double e_small = 0, e_ref = 0, e_large = 0;
  const double small = swing(4000.0, &e_small), ref = swing(40.0, &e_ref), large = swing(20.0, &e_large);
  EXPECT_NEAR(small / ref, 0.01, 0.0015);
  EXPECT_LT(large, ref);  // more compression on the smaller pulley
  for (double e : {e_small, e_ref, e_large}) EXPECT_LT(e, 1e-6);
  std::printf("gap s22 swing span -> pulley: R 4000 %.5f, R 40 %.4f, R 20 %.4f MPa\n", small, ref, large);
}

// Report I's first qualitative result: sharp stress peaks at the entrance and exit transitions.
// Mid-cushion shear in the spans (nothing bends or rubs there) stays below a third of its peak at
// the transitions (segment's middle within 25 mm of the K ramps 90–100 and 200–210 mm).
TEST(SegmentCycle, CushionShearPeaksAtTheEntranceAndExitTransitions) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult r = f.run(*bottom, *cushion);
  double spans = 0.0, entrance = 0.0, exit = 0.0;
  for (const CycleSample& q : point(r, "mid_cushion").samples) {
    const double s = q.s_mm, v = std::abs(q.s12_MPa);
    if (q.t_s <= r.cycle_time_s) continue;  // step 1
    if (s > 65.0 && s < 125.0) entrance = std::max(entrance, v);
    if (s > 175.0 && s < 235.0) exit = std::max(exit, v);
    if ((s > 10.0 && s < 55.0) || (s > 250.0 && s < 380.0)) spans = std::max(spans, v);
  }
  EXPECT_LT(3.0 * spans, entrance);
  EXPECT_LT(3.0 * spans, exit);
  std::printf("mid-cushion |s12| max: spans %.4g, entrance %.4g, exit %.4g MPa\n", spans, entrance, exit);
}

// Increments of 1/10 of the cycle run (step cuts where needed) and agree with 1/40 on the steady
// part of the wrap: the gap bottom's σ22 at s = 120 mm (pure bending, R 40 mm) within 1 %.
TEST(SegmentCycle, TenthOfACycleStepsAgreeWithFineStepsOnTheArc) {
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  auto arc_stress = [&](int steps, double* equilibrium) {
    Fixture f(synthetic_cycle(0.0));
    f.knobs.stepping.cycles = 1;
    f.knobs.stepping.steps_per_cycle = steps;
    f.knobs.stepping.change_weight = 0.0;  // equal steps: one increment is 1/steps of the cycle
    const CycleResult r = f.run(*bottom, *cushion);
    *equilibrium = r.equilibrium_error;
    for (const auto& p : r.points)
      for (const auto& q : p.samples) EXPECT_TRUE(std::isfinite(q.s11_MPa + q.s22_MPa + q.s12_MPa));
    const CycleSample& q = at(point(r, "gap_bottom"), 1, 120.0);  // the segment wholly in the wrap, F constant
    EXPECT_NEAR(q.s_mm, 120.0, 1e-9);                              // both step sizes have a sample there
    return q.s22_MPa;
  };
  double e10 = 0, e40 = 0;
  const double coarse = arc_stress(10, &e10), fine = arc_stress(40, &e40);
  ASSERT_LT(coarse, 0.0);
  EXPECT_NEAR(coarse, fine, 0.01 * std::abs(fine));
  EXPECT_LT(std::max(e10, e40), 1e-6);
  std::printf("gap s22 mid-arc: 10 steps %.5f, 40 steps %.5f MPa\n", coarse, fine);
}

// Issue 11's hard case "steps from 10⁻⁶ to 10⁻¹ of the cycle": increments of 10⁻⁶ of the cycle
// (0.4 µm of travel, 0.4 µs) in the entrance ramp converge, and each changes the stresses by no more
// than the local slope says (continuity; also for a viscoelastic law updated over dt = 10⁻⁶ of the
// cycle); increments of 10⁻¹ of the cycle across the whole entrance converge and agree with steps
// of 10⁻² on the wrap within 1 %.
// The step breakpoints over random load cycles, step counts, weights and reaches: strictly rising
// in (0, 1], the last exactly 1 (the cycle's end). The sum's share k/steps of the total once
// rounded above the total for k = steps and read one past the table's end (found by the sanitizer
// build on a random drive of SceneLife.RandomDrivesAtTheElasticLevelGiveALifeOrARefusal); 10 of
// these 200 trials round so, and the address sanitizer stops the old code on them.
TEST(SegmentCycle, BreakpointsRiseToTheCyclesEndForAnyStepCount) {
  core::Rng rng(2811);
  for (int trial = 0; trial < 200; ++trial) {
    const belt::LoadCycle cycle = synthetic_cycle(rng.uniform(0.05, 2.0), rng.uniform(25.0, 200.0), rng.uniform(0.1, 0.9));
    const belt::LoadHistory h(cycle, [] { belt::BeltSection b; b.c_N = 44000.0; return b; }(), 20.0);
    const int steps = 1 + static_cast<int>(rng.uniform(0.0, 400.0));
    const double weight = rng.uniform(0.0, 20.0), reach = rng.uniform(0.0, 40.0);
    const std::vector<double> tau = cycle_breakpoints(h, steps, weight, reach);
    ASSERT_FALSE(tau.empty());
    ASSERT_LE(tau.size(), static_cast<std::size_t>(steps)) << trial;
    EXPECT_EQ(tau.back(), 1.0) << trial << ": steps " << steps << ", weight " << weight;
    EXPECT_GT(tau.front(), 0.0) << trial;
    for (std::size_t k = 1; k < tau.size(); ++k) ASSERT_GT(tau[k], tau[k - 1]) << trial << " at " << k;
  }
}

TEST(SegmentCycle, StepsFromAMillionthToATenthOfTheCycle) {
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const ContractLaw& visco = prony_point();
  const double L = 400.0, tiny = 1e-6 * L;
  for (int law = 0; law < 2; ++law) {
    Fixture f;
    f.knobs.stepping.positions_mm = {30.0, 60.0, 80.0, 88.0, 92.0, 94.0, 95.0};
    for (int k = 1; k <= 4; ++k) f.knobs.stepping.positions_mm.push_back(95.0 + k * tiny);
    const CycleResult r = law == 0 ? f.run(*bottom, *cushion) : f.run(visco, visco);
    EXPECT_EQ(r.cuts, 0);
    EXPECT_LT(r.equilibrium_error, 1e-6);
    for (const char* name : {"gap_bottom", "mid_cushion"}) {
      const std::vector<CycleSample>& q = point(r, name).samples;
      ASSERT_EQ(q.size(), static_cast<std::size_t>(f.knobs.stepping.bend_steps) + f.knobs.stepping.positions_mm.size());
      const std::size_t n = q.size();
      for (const CycleSample& c : q) ASSERT_TRUE(std::isfinite(c.s11_MPa + c.s22_MPa + c.s12_MPa + c.s33_MPa));
      EXPECT_NEAR(q[n - 1].s_mm - q[n - 5].s_mm, 4 * tiny, 1e-12);
      // Slope over the last millimetre (94 → 95 mm), per µ-step.
      const double slope22 = std::abs(q[n - 5].s22_MPa - q[n - 6].s22_MPa) * tiny;
      const double slope12 = std::abs(q[n - 5].s12_MPa - q[n - 6].s12_MPa) * tiny;
      for (std::size_t k = n - 4; k < n; ++k) {
        EXPECT_LE(std::abs(q[k].s22_MPa - q[k - 1].s22_MPa), 3.0 * slope22 + 1e-8) << name << ' ' << k;
        EXPECT_LE(std::abs(q[k].s12_MPa - q[k - 1].s12_MPa), 3.0 * slope12 + 1e-8) << name << ' ' << k;
      }
      std::printf("%s %s: s22 %.9f -> %.9f MPa over 4 steps of 1e-6 cycle (slope x step %.3g MPa)\n",
                  law == 0 ? "hencky" : "prony", name, q[n - 5].s22_MPa, q[n - 1].s22_MPa, slope22);
    }
  }
  // Tenths of the cycle (the 80 → 120 mm increment takes the whole entrance) against hundredths.
  auto wrap_stress = [&](double step_mm, const PlaneStrainLaw& b, const PlaneStrainLaw& c, int* increments) {
    Fixture f;
    for (double s = step_mm; s <= 120.0 + 1e-9; s += step_mm) f.knobs.stepping.positions_mm.push_back(s);
    const CycleResult r = f.run(b, c);
    *increments = r.increments;
    const CycleSample& q = point(r, "gap_bottom").samples.back();
    EXPECT_NEAR(q.s_mm, 120.0, 1e-9);
    EXPECT_TRUE(std::isfinite(q.s22_MPa));
    return q.s22_MPa;
  };
  // The elastic law is path independent: only convergence is at stake. The viscoelastic one
  // integrates over the path: the time step's error shows — backward Euler over one step of a
  // tenth of the cycle across the whole entrance is 1.2 % off the hundredths (0.14 % while the
  // solver still cut that step in two, before the rotated predictor).
  for (int law = 0; law < 2; ++law) {
    const PlaneStrainLaw& b = law == 0 ? *bottom : static_cast<const PlaneStrainLaw&>(visco);
    const PlaneStrainLaw& c = law == 0 ? *cushion : static_cast<const PlaneStrainLaw&>(visco);
    int n_tenth = 0, n_hundredth = 0;
    const double tenth = wrap_stress(0.1 * L, b, c, &n_tenth), hundredth = wrap_stress(0.01 * L, b, c, &n_hundredth);
    ASSERT_LT(hundredth, 0.0);
    EXPECT_NEAR(tenth, hundredth, (law == 0 ? 1e-6 : 0.02) * std::abs(hundredth));
    std::printf("%s gap s22 at 120 mm: steps of 1/10 %.6f (%d increments), 1/100 %.6f MPa (%d increments)\n",
                law == 0 ? "hencky" : "prony", tenth, n_tenth, hundredth, n_hundredth);
  }
}

// A curvature jump (a pulley entered without a ramp) passing the middle of the cord curve's first
// interval: the interval's curvature is the history's mean over it, so the cord line moves
// continuously and a step of 10⁻⁶ of the cycle across that instant changes the stresses no more
// than its neighbours (a sample at the interval's middle turned the curve beyond by ds·K at once).
TEST(SegmentCycle, CurvatureJumpPassingTheCordCurveMovesItContinuously) {
  belt::LoadCycle c = synthetic_cycle(0.0);
  c.samples[2].s_mm = 90.0, c.samples[2].t_s = 0.09;  // K jumps from 0 to 1/40 at s = 90 mm
  Fixture f(c);
  const double L = 400.0, tiny = 1e-6 * L;
  const double ds = 1.5 * build_mesh(CogSection{}, f.mesh).half_length_mm / 24.0;
  const double crossing = 90.0 - 0.5 * ds;  // the first interval's middle (ahead of the segment's) meets the jump
  f.knobs.stepping.positions_mm = {30.0, 60.0, 75.0, 80.0, crossing - 3 * tiny};
  for (int k = -2; k <= 3; ++k) f.knobs.stepping.positions_mm.push_back(crossing + (k - 0.5) * tiny);
  const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult r = f.run(*bottom, *cushion);
  const std::vector<CycleSample>& q = point(r, "gap_bottom").samples;
  const std::size_t n = q.size();
  double across = 0.0, others = 0.0;
  for (std::size_t k = n - 5; k < n; ++k) {  // steps of 10⁻⁶ of the cycle; n − 3 is the one across
    const double change = std::abs(q[k].s22_MPa - q[k - 1].s22_MPa);
    (k == n - 3 ? across : others) = std::max(k == n - 3 ? across : others, change);
  }
  EXPECT_LE(across, 3.0 * others + 1e-7);
  std::printf("gap s22 change per 1e-6 cycle: across the interval middle %.3g, others <= %.3g MPa\n", across, others);
}

// The body forces (6.6)–(6.7) take μ from the load cycle's friction used: the drive's μ, ramped
// to zero and back at the driver's exit (belt-mechanics.md §2.5), as the beam level does. With the
// drive's μ instead, the friction reversed in full at the exit: a peeling transient at mid-cushion
// that the ramp exists to avoid.
TEST(SegmentCycle, BodyForcesUseTheLoadCyclesFrictionUsedThroughTheDriverExitRamp) {
  belt::LoadCycle c = synthetic_cycle();
  for (belt::LoadSample& q : c.samples)
    if (q.s_mm == 200.0) q.friction_used = 0.0;  // the ramp's middle at 200 mm
  const belt::LoadHistory h(c, [] { belt::BeltSection b; b.c_N = 44000.0; return b; }(), 20.0);
  CycleDrive d;
  d.history = &h;
  d.wedge_half_angle_rad = 19.0 * M_PI / 180.0;
  const double area = 0.8 * 2.0 / d.width_mm / std::cos(d.wedge_half_angle_rad);  // p 0.8 MPa at 200 mm
  const belt::LoadState at_ramp = h.at_position(200.0), before = h.at_position(170.0);
  EXPECT_DOUBLE_EQ(at_ramp.friction_used, 0.0);
  const Eigen::Vector2d b0 = contact_body_force(at_ramp, d);
  EXPECT_NEAR(b0.x(), 0.0, 1e-15);                                          // no friction along the belt
  EXPECT_NEAR(b0.y(), area * std::sin(d.wedge_half_angle_rad), 1e-12);     // the wedge alone (V = 0)
  // Between samples μ is interpolated like p and γ: at 170 mm, 0.8 × (1 − 9.999/39.999).
  EXPECT_NEAR(before.friction_used, 0.8 * (1.0 - (170.0 - 160.001) / (200.0 - 160.001)), 1e-9);
  const Eigen::Vector2d b1 = contact_body_force(before, d);
  const double a1 = before.p_MPa * 2.0 / d.width_mm / std::cos(d.wedge_half_angle_rad);
  EXPECT_NEAR(b1.x(), -before.friction_used * a1 * std::sin(before.gamma_rad), 1e-12);
}

// Each element's contact body force is its mean over its path extent (CyclePhysics::
// body_force_sampling_mm): where the contact ends at once, the total force on the segment falls
// smoothly as the end passes, instead of by one element's share whenever an element's centre
// passes it (the gap bottom's exit hump showed those steps: docs/segment.md).
TEST(SegmentCycle, ContactForceLeavesTheElementsGraduallyWhereTheContactEnds) {
  belt::LoadCycle c = synthetic_cycle();
  c.samples[6].s_mm = 200.001, c.samples[6].t_s = 0.200001;  // p 0.8 MPa → 0 at 200 mm
  auto largest_step = [&c](double sampling_mm) {
    Fixture f(c);
    f.knobs.physics.body_force_sampling_mm = sampling_mm;
    f.knobs.stepping.positions_mm = {50.0, 100.0, 150.0, 180.0, 190.0, 196.0};
    for (int k = 0; k <= 80; ++k) f.knobs.stepping.positions_mm.push_back(198.0 + 0.05 * k);
    const auto bottom = hencky(20.0, 0.49), cushion = hencky(8.0, 0.49);
    const CycleResult r = f.run(*bottom, *cushion);
    double step = 0.0, total = 0.0;
    for (std::size_t k = r.loads.size() - 80; k < r.loads.size(); ++k) {
      step = std::max(step, (r.loads[k].body_force_N_mm - r.loads[k - 1].body_force_N_mm).norm());
      total = std::max(total, r.loads[k - 1].body_force_N_mm.norm());
    }
    return std::make_pair(step, total);
  };
  const auto [mean_step, mean_total] = largest_step(0.1);
  const auto [centre_step, centre_total] = largest_step(0.0);
  std::printf("largest change of the contact force per 0.05 mm: element means %.4g, centres %.4g N/mm (of %.4g)\n",
              mean_step, centre_step, centre_total);
  EXPECT_GT(centre_step, 0.02 * centre_total);  // the centres switch whole elements
  EXPECT_LT(mean_step, 0.3 * centre_step);
  EXPECT_NEAR(mean_total / centre_total, 1.0, 0.05);
}

// Per-element laws (CyclePhysics::element_laws; docs/segment.md "One secant per element"): a law given
// to every bottom element replaces the role's law there and nowhere else, so a run with a soft role law
// and the stiff law on each bottom element is bit-identical to the run with the stiff role law; each
// element's recorded mean (CycleOutputs::record_elements) has the trace e11 + e22 = ln det F averaged
// over its integration points (the logarithmic strain's trace in any frame).
TEST(SegmentCycle, ElementLawsReplaceTheRolesLawElementByElementAndTheElementMeansAreRecorded) {
  Fixture f;
  f.knobs.stepping.cycles = 1;
  f.knobs.outputs.record_elements = true;
  const auto stiff = hencky(20.0, 0.49), soft = hencky(5.0, 0.49), cushion = hencky(8.0, 0.49);
  const CycleResult role = f.run(*stiff, *cushion);
  ASSERT_EQ(static_cast<int>(role.element_means.size()), role.elements);
  const CycleResult soft_role = f.run(*soft, *cushion);
  for (const MonitoredHistory& e : role.element_means) {
    f.knobs.physics.element_laws.push_back(e.role == Role::bottom ? stiff.get() : nullptr);
    ASSERT_EQ(e.samples.size(), static_cast<std::size_t>(role.increments));
  }
  const CycleResult element = f.run(*soft, *cushion);
  ASSERT_EQ(element.points.size(), role.points.size());
  for (std::size_t k = 0; k < role.points.size(); ++k)
    for (std::size_t i = 0; i < role.points[k].samples.size(); ++i) {
      const CycleSample &a = role.points[k].samples[i], &b = element.points[k].samples[i];
      ASSERT_EQ(a.s11_MPa, b.s11_MPa) << role.points[k].point.name << " " << i;
      ASSERT_EQ(a.s22_MPa, b.s22_MPa);
      ASSERT_EQ(a.e12, b.e12);
    }
  EXPECT_EQ(element.final_state.state, role.final_state.state);
  // The soft role law does change the run (the replacement is not a no-op).
  EXPECT_NE(point(soft_role, "gap_bottom").samples.back().e22, point(role, "gap_bottom").samples.back().e22);
  for (std::size_t e = 0; e < role.element_means.size(); ++e) {
    double trace = 0.0;
    for (const IntegrationPointStress& ip : role.final_state.points[e]) trace += std::log(ip.F.determinant());
    trace /= role.final_state.points[e].size();
    const CycleSample& last = role.element_means[e].samples.back();
    ASSERT_NEAR(last.e11 + last.e22, trace, 1e-12) << e;
  }
  f.knobs.physics.element_laws.pop_back();  // one law short of the mesh
  EXPECT_THROW(f.run(*soft, *cushion), core::UsageError);
}
