// The failure diagnosis (SolverKnobs::diagnose_failure; docs/segment.md §Solver, "Failure
// diagnosis"): a law whose tangent is wrong by a known factor is named with that error, a
// consistent one is not; the eigenvalue and line-scan findings are reported.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "fitlib/core/error.hpp"
#include "fitlib/segment/elastic.hpp"
#include "fitlib/segment/mesh.hpp"
#include "fitlib/segment/solver.hpp"

using namespace fitlib::segment;

namespace {

// A law whose dP/dF is the inner law's times `factor` (P unchanged): a known tangent error.
class ScaledTangentLaw final : public PlaneStrainLaw {
 public:
  ScaledTangentLaw(const PlaneStrainLaw& inner, double factor) : inner_(inner), factor_(factor) {}
  using PlaneStrainLaw::respond;
  PointResponse respond(const Matrix2& F, const PointStep& step) const override {
    PointResponse r = inner_.respond(F, step);
    r.A *= factor_;
    return r;
  }

 private:
  const PlaneStrainLaw& inner_;
  double factor_;
};

// A strip stretched by 20 % in one increment of at most two assemblies: Newton cannot converge,
// and the exit-4 message carries the diagnosis.
std::string failure_message(const PlaneStrainLaw& law) {
  CogSection s;
  s.height_mm = 2.0, s.cushion_mm = 1.0, s.cog_depth_mm = 0.0, s.root_fillet_mm = s.tip_radius_mm = 0.0;
  s.cog_pitch_mm = 4.0;
  MeshKnobs k;
  k.central_pitches = 1.0, k.end_pitches = 0.5, k.fine_size_mm = 1.0, k.coarse_size_mm = 1.0, k.cushion_rows = 1;
  const Mesh m = build_mesh(s, k);
  StaticProblem p;
  p.mesh = &m;
  p.laws = {&law, &law};
  for (int n : m.left_nodes) p.constraints.push_back({n, 0.0, {true, true}});
  for (int n : m.right_nodes) p.constraints.push_back({n, 0.0, {true, false}});
  p.motion = prescribed([&](double lambda, std::vector<std::array<double, 2>>& v) {
    for (std::size_t c = 0; c < p.constraints.size(); ++c)
      v[c] = {m.X[p.constraints[c].node].x() > 0.0 ? lambda * 0.2 * 2.0 * m.half_length_mm : 0.0, 0.0};
  });
  SolverKnobs knobs;
  knobs.stepping.steps = 1, knobs.newton.max_iterations = 2, knobs.stepping.max_cuts = 0, knobs.newton.levenberg = 0.0;
  knobs.diagnose_failure = true;
  try {
    solve_static(p, knobs);
  } catch (const fitlib::core::NumericalError& e) {
    return e.what();
  }
  return "";
}

double number_after(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key);
  return at == std::string::npos ? -1.0 : std::strtod(text.c_str() + at + key.size(), nullptr);
}

}  // namespace

TEST(SegmentDiagnosis, NamesATangentWrongByAKnownFactorAndClearsAConsistentOne) {
  const auto neo = make_elastic(ElasticLaw::neo_hookean, 20.0, 0.45);
  const std::string good = failure_message(*neo);
  const std::string bad = failure_message(ScaledTangentLaw(*neo, 0.7));
  ASSERT_NE(good.find("[increment start]"), std::string::npos) << good;
  ASSERT_NE(bad.find("[best iterate]"), std::string::npos) << bad;
  // Every column, element and point of the scaled law is off by 0.3/0.7 of its own tangent.
  EXPECT_LT(number_after(good, "worst column "), 1e-6) << good;
  EXPECT_LT(number_after(good, "dP/dF error "), 1e-6) << good;
  EXPECT_NEAR(number_after(bad, "worst column "), 0.3 / 0.7, 1e-4) << bad;
  EXPECT_NEAR(number_after(bad, "dP/dF error "), 0.3 / 0.7, 1e-4) << bad;
  EXPECT_GE(number_after(bad, "worst element "), 0.0);  // an element is named
  // A stretched neo-Hookean strip is stable: no negative eigenvalue; the residual is smooth, so a
  // tiny step along Newton's direction lowers it by that fraction.
  const std::string best = good.substr(good.find("[best iterate]"));
  EXPECT_NE(best.find(" 0 negative"), std::string::npos) << good;
  EXPECT_NEAR(number_after(best, "1e-06: "), 1.0 - 1e-6, 1e-9) << good;
  EXPECT_LT(number_after(best, " 1: "), 0.1) << good;  // Newton's full step: quadratic convergence
}
