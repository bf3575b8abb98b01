// The energy a material point dissipates over a steady strain cycle is its stress work ∮ σ dε
// (the segment's complete-level hysteresis, docs/thermal.md §1, takes it so for every model):
// a Prony (generalised Zener) point sheared at γ_a sin ωt dissipates π G″(f) γ_a² per unit volume
// and cycle, the closed form of the ellipse; an elastic point dissipates nothing.
#include <gtest/gtest.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "fitlib/model/material_point.hpp"
#include "fitlib/model/model.hpp"

namespace {

using namespace fitlib::model;

// ∮ σ12 dγ12 over the last of `cycles` cycles of γ12 = γ_a sin(2π f t), trapezoidal on `steps` per cycle.
double last_cycle_work(const MaterialPoint& point, double gamma_a, double f_Hz, int cycles, int steps) {
  std::vector<double> x = point.initial_state(), next(point.state_size());
  const double dt = 1.0 / (f_Hz * steps);
  Vector6 e = Vector6::Zero(), s_last = Vector6::Zero();
  double work = 0.0;
  for (int n = 1; n <= cycles * steps; ++n) {
    Vector6 e_next = Vector6::Zero();
    e_next[5] = gamma_a * std::sin(2.0 * M_PI * f_Hz * n * dt);
    const Vector6 s = point.update(x.data(), e_next, dt, NAN, next.data());
    if (n > (cycles - 1) * steps) work += 0.5 * (s[5] + s_last[5]) * (e_next[5] - e[5]);
    x.swap(next), e = e_next, s_last = s;
  }
  return work;
}

TEST(CycleDissipation, PronyPointShearedSinusoidallyDissipatesPiGLossGammaSquared) {
  const auto model = make_model("prony", {{"terms", 2}, {"mode", "shear"}});
  const std::vector<double> values{1.0, 2.0, 3.0, 0.002, 0.02};  // G∞, G1, G2 (MPa), τ1, τ2 (s)
  PointOptions o;
  o.bulk_modulus_MPa = 2000.0;
  const auto point = make_material_point(*model, values, o);
  const double f = 30.0, gamma_a = 0.05;
  const double G_loss = point->complex_stiffness(f, NAN)(5, 5).imag();
  ASSERT_GT(G_loss, 0.5);
  // 12 cycles: the slowest term (τ 0.02 s against a 0.033 s period) has settled to e^-(12 / 0.6)
  const double w = last_cycle_work(*point, gamma_a, f, 12, 800);
  EXPECT_NEAR(w / (M_PI * G_loss * gamma_a * gamma_a), 1.0, 1e-4);
}

TEST(CycleDissipation, ElasticPointDissipatesNothing) {
  const auto point = make_material_point(*make_model("elastic-iso", {}), {10.0, 0.45});
  EXPECT_NEAR(last_cycle_work(*point, 0.05, 30.0, 2, 400), 0.0, 1e-15);
}

}  // namespace
