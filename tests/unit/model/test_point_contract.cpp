// The material-point contract suite (docs/model.md §"The point suite"), MTest-style: one
// parameterised test that every model's point passes.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/model.hpp"

namespace {

using namespace fitlib::model;
using fitlib::core::kPi;

struct Case {
  std::string name;
  std::string kind;
  nlohmann::json options;
  std::vector<double> values;  // empty: read from `card` (a repository dataset)
  std::string card;
  PointOptions point;
  int order = 2;                 // recurrence order in dt; 0 = exact (elastic)
  // Relative to |C*| of the column, steady sinusoid vs complex stiffness. Fritzson: 1e-2, its
  // running mean (1/t)∫e of a sine decays only as 1/(ωt) (≈ 0.2 % of |C*| after 40 cycles).
  double steady_tolerance = 1e-4;
  bool creep = true;             // the model has a creep compliance closed form
  std::string orientation = "12";
  // Relative, held step vs the relaxation modulus: 1e-6 where the recurrence is exact for
  // piecewise-linear strain; the backward-Euler Fritzson scheme is first order on the log grid.
  double relaxation_tolerance = 1e-6;
};

std::vector<double> card_values(const std::string& relative) {
  std::ifstream in(std::string(FITLIB_SOURCE_DIR) + "/" + relative);
  const nlohmann::json j = nlohmann::json::parse(in);
  std::vector<double> v;
  for (const auto& p : j["parameters"]) v.push_back(p["value"].get<double>());
  return v;
}

PointOptions elastic_at(double f, double T) {
  PointOptions o;
  o.fidelity = fitlib::core::Fidelity::elastic;
  o.frequency_Hz = f;
  o.temperature_C = T;
  return o;
}

PointOptions fritzson_exponential() {
  PointOptions o;
  o.fritzson_exponential = true;
  return o;
}

const nlohmann::json kShearK = {{"mode", "shear"}, {"bulk_modulus", true}, {"terms", 3}};
const nlohmann::json kShearKNoTerms = {{"mode", "shear"}, {"bulk_modulus", true}};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

std::vector<Case> cases() {
  nlohmann::json wlf = kShearK;
  wlf["temperature_law"] = "wlf";
  wlf["reference_C"] = 23.0;
  return {
      {"elastic_iso", "elastic-iso", {}, {10.0, 0.45}, "", {}, 0},
      {"elastic_ortho", "elastic-ortho", {}, {5.0, 8.0, 200.0, 0.4, 0.01, 0.01, 2.0, 3.0, 3.5}, "", {}, 0},
      {"prony", "prony", kShearK, {1.0, 2.0, 1.5, 0.8, 0.01, 0.1, 0.5, 500.0}, "", {}},
      {"prony_wlf", "prony", wlf, {1.0, 2.0, 1.5, 0.8, 0.01, 0.1, 0.5, 500.0, 8.0, 120.0}, "", {}},
      {"zener3", "zener3", kShearKNoTerms, {2.0, 0.05, 0.2, 500.0}, "", {}},
      {"retardation", "retardation", kShearK, {0.1, 0.2, 0.3, 0.1, 0.02, 0.1, 0.4, 500.0}, "", {}},
      {"fractional_zener", "fractional-zener", kShearKNoTerms, {1.0, 5.0, 0.05, 0.5, 500.0}, "", {}},
      {"prony_elastic", "prony", kShearK, {1.0, 2.0, 1.5, 0.8, 0.01, 0.1, 0.5, 500.0}, "", elastic_at(2.0, NAN), 0},
      {"fritzson_iso", "fritzson-iso", {}, {}, "datasets/cards/material-2-true.json", {}, 1, 1e-2, false, "12", 5e-4},
      {"fritzson", "fritzson", {}, {}, "datasets/cards/material-1-true.json", {}, 1, 1e-2, false, "23", 5e-4},
      {"fritzson_exp", "fritzson", {}, {}, "datasets/cards/material-1-true.json", fritzson_exponential(), 1, 1e-2, false, "13"},
  };
}

class PointContract : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override {
    const Case& c = GetParam();
    model_ = make_model(c.kind, c.options);
    values_ = c.values.empty() ? card_values(c.card) : c.values;
    point_ = make_material_point(*model_, values_, c.point);
  }
  // A mixed strain path through all six components (γ small enough for Fritzson's range).
  static Vector6 path(double t) {
    Vector6 e;
    for (int i = 0; i < 6; ++i) e[i] = 1e-3 * (i + 1) * std::sin(2.0 * kPi * (0.7 + 0.13 * i) * t + i);
    return e;
  }
  int component() const {
    const std::string& o = GetParam().orientation;
    const int i = o[0] - '1', j = o[1] - '1';
    return i == j ? i : (i + j == 3) ? 3 : (i + j == 2) ? 4 : 5;
  }
  ModelPtr model_;
  std::vector<double> values_;
  MaterialPointPtr point_;
};

// Central differences of the update against its consistent tangent after a loaded history.
TEST_P(PointContract, TangentMatchesFiniteDifferences) {
  std::vector<double> state = point_->initial_state(), next(point_->state_size());
  const double dt = 0.01;
  for (int n = 0; n < 20; ++n) {
    point_->update(state.data(), path(n * dt), n ? dt : 0.0, 30.0, next.data());
    state.swap(next);
  }
  const Vector6 e = path(20 * dt);
  Matrix6 C, C_fd;
  point_->update(state.data(), e, dt, 30.0, next.data(), &C);
  for (int j = 0; j < 6; ++j) {
    const double h = 1e-7;
    Vector6 ep = e, em = e;
    ep[j] += h;
    em[j] -= h;
    C_fd.col(j) = (point_->update(state.data(), ep, dt, 30.0, next.data()) -
                   point_->update(state.data(), em, dt, 30.0, next.data())) / (2.0 * h);
  }
  EXPECT_LE((C - C_fd).norm(), 1e-6 * C.norm()) << "tangent\n" << C << "\nfd\n" << C_fd;
}

// A steady small sinusoid on one strain component (all others zero): σ̂ = C*(ω) ε̂ column-wise.
TEST_P(PointContract, SteadySinusoidMatchesComplexStiffness) {
  const double f = 2.0, amplitude = 1e-7;
  const int k = component(), cycles = 40, per_cycle = 2000;
  std::vector<double> state = point_->initial_state(), next(point_->state_size());
  const double dt = 1.0 / f / per_cycle;
  std::array<std::complex<double>, 6> sigma_hat{};
  for (int n = 0; n <= cycles * per_cycle; ++n) {
    const double t = n * dt;
    Vector6 e = Vector6::Zero();
    e[k] = amplitude * std::sin(2.0 * kPi * f * t);
    const Vector6 s = point_->update(state.data(), e, n ? dt : 0.0, NAN, next.data());
    state.swap(next);
    if (n > (cycles - 1) * per_cycle) {  // rectangle rule over the last period (periodic)
      const std::complex<double> w = std::exp(std::complex<double>(0.0, -2.0 * kPi * f * t));
      for (int i = 0; i < 6; ++i) sigma_hat[i] += s[i] * w / double(per_cycle);
    }
  }
  // ε = a sin ωt → ε̂ = a/(2i) in the same projection.
  const std::complex<double> eps_hat = amplitude / std::complex<double>(0.0, 2.0);
  const ComplexMatrix6 C = point_->complex_stiffness(f, NAN);
  for (int i = 0; i < 6; ++i)
    EXPECT_LE(std::abs(sigma_hat[i] / eps_hat - C(i, k)), GetParam().steady_tolerance * C.col(k).norm())
        << "row " << i << ": " << sigma_hat[i] / eps_hat << " vs " << C(i, k);
}

// Stress at t = 0.5 s of a smooth path with 25, 50, 100 steps against 800: the error ratio per
// halving is 2^order.
TEST_P(PointContract, RecurrenceConvergesWithItsOrder) {
  auto run = [&](int steps) {
    std::vector<double> state = point_->initial_state(), next(point_->state_size());
    Vector6 s;
    for (int n = 0; n <= steps; ++n) {
      s = point_->update(state.data(), path(0.5 * n / steps), n ? 0.5 / steps : 0.0, NAN, next.data());
      state.swap(next);
    }
    return s;
  };
  const Vector6 reference = run(3200);
  const double e1 = (run(50) - reference).norm(), e2 = (run(100) - reference).norm();
  const int order = GetParam().order;
  if (order == 0) {
    EXPECT_LE(e1, 1e-12 * reference.norm());
    return;
  }
  const double rate = std::log2(e1 / e2);
  EXPECT_NEAR(rate, order, 0.25) << "errors " << e1 << ", " << e2;
}

// F = Q(t) U(t) with a growing rigid rotation Q gives the same unrotated stress and state as U.
TEST_P(PointContract, RigidRotationLeavesTheMaterialFrameStressUnchanged) {
  std::vector<double> a = point_->initial_state(), b = a, next(point_->state_size());
  for (int n = 0; n <= 10; ++n) {
    const double t = 0.01 * n;
    const Vector6 e = path(t);
    Eigen::Matrix3d U;
    U << 1 + e[0], 0.5 * e[5], 0.5 * e[4], 0.5 * e[5], 1 + e[1], 0.5 * e[3], 0.5 * e[4], 0.5 * e[3], 1 + e[2];
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.3 * n, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    Vector6 sa, sb;
    point_->update_deformation(a.data(), U, n ? 0.01 : 0.0, NAN, next.data(), &sa);
    a.swap(next);
    const Eigen::Matrix3d tau = point_->update_deformation(b.data(), Q * U, n ? 0.01 : 0.0, NAN, next.data(), &sb);
    b.swap(next);
    EXPECT_LE((sa - sb).norm(), 1e-9 * (1.0 + sa.norm())) << "step " << n;
    Eigen::Matrix3d S;
    S << sb[0], sb[5], sb[4], sb[5], sb[1], sb[3], sb[4], sb[3], sb[2];
    EXPECT_LE((tau - Q * S * Q.transpose()).norm(), 1e-9 * (1.0 + S.norm()));
  }
}

// A shear strain step held: σ/γ0 = the model's relaxation modulus; a shear stress step held
// (every other stress zero): γ/σ0 = its creep compliance.
TEST_P(PointContract, RelaxationAndCreepMatchTheModel) {
  TestCondition c;
  c.mode = TestMode::shear;
  c.orientation = GetParam().orientation;
  const int k = component();
  std::vector<double> times{0.0};
  for (int n = 0; n <= 600; ++n) times.push_back(1e-4 * std::pow(10.0, n / 150.0));  // to 10 s
  const double gamma0 = 1e-3;
  DriveProgram relax;
  relax.time_s = times;
  for (int i = 0; i < 6; ++i) relax.components[i].imposed = DriveControl::Imposed::strain;
  relax.components[k].values.assign(times.size(), gamma0);
  const DriveResult r = drive(*point_, relax);
  const bool elastic = GetParam().point.fidelity == fitlib::core::Fidelity::elastic;
  c.frequency_Hz = GetParam().point.frequency_Hz;
  for (size_t n = 0; n < times.size(); n += 100) {
    // The elastic equivalent holds the storage modulus at its frequency.
    const double expected = elastic ? model_->moduli(values_.data(), c).storage
                                    : model_->relaxation_modulus(values_.data(), c, times[n]);
    EXPECT_NEAR(r.stress[n][k] / gamma0, expected,
                GetParam().relaxation_tolerance * r.stress[0][k] / gamma0) << "t = " << times[n];
  }
  if (!GetParam().creep || elastic) return;
  DriveProgram creep;
  creep.time_s = times;
  const double sigma0 = 1e-3;
  creep.components[k].values.assign(times.size(), sigma0);
  const DriveResult cr = drive(*point_, creep);
  for (size_t n = 0; n < times.size(); n += 100)
    EXPECT_NEAR(cr.strain[n][k] / sigma0, model_->creep_compliance(values_.data(), c, times[n]),
                1e-3 * cr.strain.back()[k] / sigma0) << "t = " << times[n];
}

// Stop, write the state to JSON text, read it back, continue: the same bits as never stopping.
TEST_P(PointContract, RestartFromSerialisedStateIsBitIdentical) {
  std::vector<double> state = point_->initial_state(), next(point_->state_size());
  std::vector<Vector6> straight;
  for (int n = 0; n < 40; ++n) {
    straight.push_back(point_->update(state.data(), path(0.01 * n), n ? 0.01 : 0.0, 40.0, next.data()));
    state.swap(next);
  }
  state = point_->initial_state();
  for (int n = 0; n < 20; ++n) {
    point_->update(state.data(), path(0.01 * n), n ? 0.01 : 0.0, 40.0, next.data());
    state.swap(next);
  }
  const std::string text = point_->state_to_json(state.data()).dump();
  std::vector<double> restored = point_->state_from_json(nlohmann::json::parse(text));
  for (int n = 20; n < 40; ++n) {
    const Vector6 s = point_->update(restored.data(), path(0.01 * n), 0.01, 40.0, next.data());
    restored.swap(next);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(s[i], straight[n][i]) << "step " << n;
  }
}

// A non-finite input to the driver (time, a component's value, an infinite temperature) is bad
// input naming the sample, not a NaN stress or "stress control did not converge"; a non-finite
// parameter names the parameter.
TEST_P(PointContract, NonFiniteInputIsRefusedNamingTheSampleOrParameter) {
  DriveProgram p;
  p.time_s = {0.0, 0.5, 1.0};
  p.components[0].values = {0.0, 1e-3, 2e-3};  // ε11 imposed, the others stress-free
  p.components[0].imposed = DriveControl::Imposed::strain;
  EXPECT_NO_THROW(drive(*point_, p));
  const auto refused = [&](DriveProgram bad, const std::string& says) {
    try {
      drive(*point_, bad);
      ADD_FAILURE() << "accepted: " << says;
    } catch (const fitlib::core::UsageError& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  };
  DriveProgram bad = p;
  bad.components[0].values[1] = std::nan("");
  refused(bad, "component 1 is not finite at sample 1");
  bad = p, bad.components[3].values = {0.0, 0.0, INFINITY};  // σ23 imposed (stress control)
  refused(bad, "component 4 is not finite at sample 2");
  bad = p, bad.time_s[2] = INFINITY;
  refused(bad, "time 2 is not finite");
  bad = p, bad.temperature_C = {40.0, -INFINITY, 40.0};
  refused(bad, "temperature 1 is infinite");
  bad = p, bad.temperature_C = {40.0, std::nan(""), 40.0};  // NaN = the reference temperature
  EXPECT_NO_THROW(drive(*point_, bad));
  // Nor does a point take a non-finite parameter (it reached every stress as NaN).
  std::vector<double> values = values_;
  values.back() = std::nan("");
  try {
    make_material_point(*model_, values, GetParam().point);
    ADD_FAILURE() << "a NaN parameter was accepted";
  } catch (const fitlib::core::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("parameter '" + model_->parameters().back().name + "'"), std::string::npos)
        << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(EveryModel, PointContract, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.name; });

}  // namespace
