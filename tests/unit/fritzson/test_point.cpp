// Time-domain integration at a material point: consistent tangent, steady state against the
// complex form for all seven test types, order of convergence, damage evolution, and the hard
// cases (t → 0, step sizes, large C_d, K/G up to 10⁶, log strain).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/model/fritzson.hpp"
#include "fitlib/model/fritzson_point.hpp"
#include "materials.hpp"
#include "fitlib/core/units.hpp"

namespace {

using namespace fitlib::model;
using namespace fitlib::model::fritzson;
// fritzson's own point and driver (model:: has the generic ones of the same names)
using fitlib::model::fritzson::DriveResult;
using fitlib::model::fritzson::MaterialPoint;
using fritzson_test::material1_parameters;
using fritzson_test::material2_parameters;

using fitlib::core::kPi;

TestCondition condition(TestMode mode, const std::string& orientation, double f, double T,
                        double amplitude, double mean) {
  TestCondition c;
  c.mode = mode;
  c.orientation = orientation;
  c.frequency_Hz = f;
  c.temperature_C = T;
  c.strain_amplitude = amplitude;
  c.mean_strain = mean;
  return c;
}

// A state with history: a few cycles of a mixed strain path.
MaterialState state_after_history(const MaterialPoint& point, double scale) {
  MaterialState state, next;
  const int n = 200;
  for (int k = 1; k <= n; ++k) {
    const double t = k * 1e-3;
    Vector6 e;
    e << scale * std::sin(60 * t), -0.4 * scale * std::sin(60 * t), -0.5 * scale * std::sin(60 * t + 0.1),
        0.3 * scale * std::cos(50 * t), 0.2 * scale * std::sin(40 * t), 0.5 * scale * std::sin(70 * t);
    point.update(state, e, 1e-3, 60.0, next);
    state = next;
  }
  return state;
}

TEST(FritzsonPoint, ConsistentTangentMatchesCentralDifferences) {
  for (Scheme scheme : {Scheme::backward_euler, Scheme::exponential}) {
    const MaterialPoint point(material1_parameters(), true, 23.0, scheme);
    const MaterialState state = state_after_history(point, 0.01);
    // Two increments: a large one (damage evolves, e^o > e^a) and a small one (it does not).
    for (double factor : {3.0, 1.0005}) {
      Vector6 strain = state.strain * factor;
      strain[5] += 1e-4;
      MaterialState next;
      Matrix6 tangent;
      point.update(state, strain, 1e-3, 60.0, next, &tangent);
      for (int j = 0; j < 6; ++j) {
        const double h = 1e-7;
        Vector6 up = strain, down = strain;
        up[j] += h;
        down[j] -= h;
        MaterialState scratch;
        const Vector6 fd = (point.update(state, up, 1e-3, 60.0, scratch) -
                            point.update(state, down, 1e-3, 60.0, scratch)) / (2 * h);
        for (int i = 0; i < 6; ++i)
          EXPECT_NEAR(tangent(i, j), fd[i], 1e-5 * (std::abs(fd[i]) + 10.0))
              << "factor " << factor << " (" << i << "," << j << ")";
      }
    }
  }
}

TEST(FritzsonPoint, UpdateIsPureAndDtZeroIsIdempotent) {
  const MaterialPoint point(material1_parameters(), true, 23.0);
  const MaterialState state = state_after_history(point, 0.01);
  MaterialState a, b;
  const Vector6 s1 = point.update(state, state.strain, 0.0, 60.0, a);
  const Vector6 s2 = point.update(state, state.strain, 0.0, 60.0, b);
  EXPECT_EQ(s1, s2);
  const Vector6 s3 = point.update(a, state.strain, 0.0, 60.0, b);
  EXPECT_LT((s3 - s1).norm(), 1e-12 * s1.norm());
  EXPECT_THROW(point.update(state, state.strain, -1e-3, 60.0, a), fitlib::core::UsageError);
}

// Running mean at t → 0: a jump at the start leaves e^o = 0 (no dynamic stress, no damage), and
// the instantaneous shear modulus is G_Im + 5 β2 G_Iv (all five Maxwell springs, h2 = β2).
TEST(FritzsonPoint, JumpAtTimeZero) {
  const std::vector<double> p = material2_parameters();
  const MaterialPoint point(p, false, 23.0, Scheme::exponential);
  MaterialState state, next;
  Vector6 strain = Vector6::Zero();
  strain[5] = 0.01;
  const Vector6 s = point.update(state, strain, 0.0, 23.0, next);
  const double G0 = p[kPartI + kMean] + 5 * p[kPartI + kBeta2] * p[kPartI + kViscous];
  EXPECT_NEAR(s[5], G0 * 0.01, 1e-14);
  EXPECT_DOUBLE_EQ(next.driver_amplitude[0], 0.0);
  // Holding: the running mean stays equal to the strain, the Maxwell stresses relax.
  const double tau = p[kPartI + kTau];
  MaterialState held;
  const Vector6 later = point.update(next, strain, 100 * tau * 25, 23.0, held);
  EXPECT_NEAR(later[5], p[kPartI + kMean] * 0.01, 1e-6 * later[5]);
  EXPECT_DOUBLE_EQ(held.driver_amplitude[0], 0.0);
}

// The steady state of the integration (200 cycles, damage settled with the thesis's C_d = 0.6)
// equals the complex form with damage saturated, for all seven test types, at 60 °C.
TEST(FritzsonPoint, SteadyStateEqualsComplexFormForAllSevenTests) {
  const std::vector<double> p = material1_parameters();
  const auto model = make_model("fritzson", {{"reference_C", 23.0}});
  const MaterialPoint point(p, true, 23.0, Scheme::exponential);
  const double f = 10.0, T = 60.0;
  const std::vector<TestCondition> tests = {
      condition(TestMode::shear, "12", f, T, 0.02, 0.02),
      condition(TestMode::shear, "13", f, T, 0.02, 0.02),
      condition(TestMode::shear, "23", f, T, 0.02, 0.02),
      condition(TestMode::uniaxial, "11", f, T, 0.01, -0.01),
      condition(TestMode::uniaxial, "22", f, T, 0.01, -0.01),
      condition(TestMode::uniaxial, "33", f, T, 0.005, -0.005),
      condition(TestMode::bulk, "", f, T, 0.001, -0.001)};
  for (const TestCondition& c : tests) {
    const StrainHistory h = cyclic_history(c.strain_amplitude, c.mean_strain, f, 200, 128);
    const DriveResult r = drive_test(point, c, h);
    const Moduli<double> time = cycle_moduli(h.time_s, h.strain, r.stress, f);
    const Moduli<double> complex = model->moduli(p.data(), c);
    const std::string label = std::string(to_string(c.mode)) + " " + c.orientation;
    // Tolerance (docs/fritzson.md §5): 0.5 % of the storage modulus; the residue is the
    // running mean's 1/t tail and the damage still creeping towards its saturated value.
    const double tol = 5e-3 * complex.storage;
    std::printf("  %-12s storage %.3e loss %.3e mean %.3e (relative deviation)\n", label.c_str(),
                time.storage / complex.storage - 1, (time.loss - complex.loss) / complex.storage,
                time.mean / complex.mean - 1);
    EXPECT_NEAR(time.storage, complex.storage, tol) << label;
    EXPECT_NEAR(time.loss, complex.loss, tol) << label;
    EXPECT_NEAR(time.mean, complex.mean, 5e-3 * complex.mean) << label;
  }
}

// Order of convergence at a fixed time, damage held fixed (pre-damaged state): backward Euler
// is first order, the exponential scheme second order. With damage evolving backward Euler
// stays first order.
double shear_stress_at_end(const MaterialPoint& point, int steps, bool predamaged) {
  MaterialState state, next;
  if (predamaged) state.driver_amplitude = {1.0, 1.0, 1.0};
  const double f = 10.0, T_end = 0.75 / f, dt = T_end / steps;
  Vector6 strain = Vector6::Zero();
  double s = 0.0;
  for (int k = 1; k <= steps; ++k) {
    strain[5] = 0.02 * std::sin(2 * kPi * f * k * dt);
    s = point.update(state, strain, dt, 60.0, next)[5];
    state = next;
  }
  return s;
}

TEST(FritzsonPoint, ConvergenceOrder) {
  struct Case {
    Scheme scheme;
    bool predamaged;
    double order;
  };
  for (const Case& k : {Case{Scheme::backward_euler, true, 1.0}, Case{Scheme::exponential, true, 2.0},
                        Case{Scheme::backward_euler, false, 1.0}}) {
    const MaterialPoint point(material1_parameters(), true, 23.0, k.scheme);
    const double reference = shear_stress_at_end(point, 1 << 16, k.predamaged);
    const double e1 = std::abs(shear_stress_at_end(point, 400, k.predamaged) - reference);
    const double e2 = std::abs(shear_stress_at_end(point, 800, k.predamaged) - reference);
    const double e3 = std::abs(shear_stress_at_end(point, 1600, k.predamaged) - reference);
    const double order = 0.5 * (std::log2(e1 / e2) + std::log2(e2 / e3));
    EXPECT_NEAR(order, k.order, 0.15) << "scheme " << int(k.scheme) << " predamaged " << k.predamaged;
  }
}

TEST(FritzsonPoint, StepsFromMicroToDeciCycle) {
  const MaterialPoint point(material1_parameters(), true, 23.0, Scheme::exponential);
  const double f = 10.0;
  // Integrate 0.1 cycle of a sine at steps of 1e-6 … 1e-1 cycle; all agree with the finest.
  auto run = [&](double dt_cycles) {
    MaterialState state, next;
    const int steps = int(std::lround(0.1 / dt_cycles));
    const double dt = dt_cycles / f;
    Vector6 strain = Vector6::Zero(), s;
    for (int k = 1; k <= steps; ++k) {
      strain[3] = 0.01 * std::sin(2 * kPi * f * k * dt);
      s = point.update(state, strain, dt, 23.0, next);
      state = next;
    }
    return s[3];
  };
  const double finest = run(1e-6);
  for (double dt : {1e-5, 1e-4, 1e-3, 1e-2, 1e-1}) {
    const double s = run(dt);
    EXPECT_TRUE(std::isfinite(s));
    EXPECT_NEAR(s, finest, std::max(0.2 * dt, 1e-6) * std::abs(finest)) << dt;
  }
}

TEST(FritzsonPoint, LiteralDamageLawWithThesisConstant) {
  // e_o = A|sin ωt| through the law with C_d = 0.6: e_a/A = 0.63, 0.76, 0.82, 0.88, 0.93 after
  // 1, 2, 3, 5, 10 cycles (constitutive-model.md §2), independent of frequency.
  const int per_cycle = 20000;
  double ea = 0.0, eo_previous = 0.0;
  std::vector<double> at;
  for (int k = 1; k <= 10 * per_cycle; ++k) {
    const double eo = std::abs(std::sin(2 * kPi * double(k) / per_cycle));
    ea = evolve_damage_driver(ea, eo_previous, eo, 0.6);
    eo_previous = eo;
    if (k % per_cycle == 0) at.push_back(ea);
  }
  EXPECT_NEAR(at[0], 0.63, 0.01);
  EXPECT_NEAR(at[1], 0.76, 0.01);
  EXPECT_NEAR(at[2], 0.82, 0.01);
  EXPECT_NEAR(at[4], 0.88, 0.01);
  EXPECT_NEAR(at[9], 0.93, 0.01);
}

TEST(FritzsonPoint, LargeDamageConstantIsStableAndBoundedByTheDriver) {
  std::vector<double> p = material2_parameters();
  p[kCd] = 1e4;
  const MaterialPoint point(p, false, 23.0, Scheme::backward_euler);
  const double f = 10.0;
  const StrainHistory h = cyclic_history(0.02, 0.02, f, 3, 50);
  MaterialState state, next;
  double peak = 0.0;
  for (size_t n = 1; n < h.time_s.size(); ++n) {
    Vector6 strain = Vector6::Zero();
    strain[5] = h.strain[n];
    const Vector6 s = point.update(state, strain, h.time_s[n] - h.time_s[n - 1], 23.0, next);
    state = next;
    peak = std::max(peak, state.driver_oscillating[0]);
    EXPECT_TRUE(s.allFinite());
    EXPECT_LE(state.driver_amplitude[0], peak * (1 + 1e-12));
  }
  EXPECT_GT(state.driver_amplitude[0], 0.999 * peak);
}

TEST(FritzsonPoint, NearIncompressibleUniaxialFrom1e3To1e6) {
  std::vector<double> p = material2_parameters();
  const auto model = make_model("fritzson-iso", {{"reference_C", 23.0}});
  const double f = 10.0;
  for (double ratio : {1e3, 1e4, 1e5, 1e6}) {
    p[kK] = ratio * p[kPartI + kMean];
    const MaterialPoint point(p, false, 23.0, Scheme::exponential);
    const TestCondition c = condition(TestMode::uniaxial, "22", f, 23.0, 0.01, -0.01);
    const StrainHistory h = cyclic_history(0.01, -0.01, f, 40, 64);
    const DriveResult r = drive_test(point, c, h);
    const Moduli<double> time = cycle_moduli(h.time_s, h.strain, r.stress, f);
    const Moduli<double> complex = model->moduli(p.data(), c);
    EXPECT_NEAR(time.storage, complex.storage, 0.02 * complex.storage) << ratio;
    // Volume nearly constant: tr ε / ε ≤ 1/ratio-ish.
    const Vector6& e = r.strain.back();
    EXPECT_LT(std::abs(e[0] + e[1] + e[2]), 10.0 / ratio * std::abs(e[1]) + 1e-15) << ratio;
  }
}

TEST(FritzsonPoint, LogarithmicStrainVariant) {
  const MaterialPoint point(material1_parameters(), true, 23.0);
  // Pure stretch: ln U = ln λ, no rotation.
  const Eigen::Matrix3d U = Eigen::Vector3d(1.1, 0.96, 0.97).asDiagonal();
  Eigen::Matrix3d R;
  const Vector6 e = log_strain(U, &R);
  EXPECT_NEAR(e[0], std::log(1.1), 1e-15);
  EXPECT_NEAR(e[2], std::log(0.97), 1e-15);
  EXPECT_NEAR((R - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
  // A rigid rotation on top changes nothing but the frame of the Kirchhoff stress.
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  MaterialState state, a, b;
  Vector6 su, sr;
  const Eigen::Matrix3d tau_u = point.update_deformation(state, U, 1e-3, 40.0, a, &su);
  const Eigen::Matrix3d tau_r = point.update_deformation(state, Q * U, 1e-3, 40.0, b, &sr);
  EXPECT_LT((su - sr).norm(), 1e-10 * su.norm());
  EXPECT_LT((tau_r - Q * tau_u * Q.transpose()).norm(), 1e-10 * tau_u.norm());
  // Small simple shear: ln U = small strain to second order.
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 1) = 1e-3;
  const Vector6 g = log_strain(F);
  EXPECT_NEAR(g[5], 1e-3, 1e-9);
  EXPECT_NEAR(g[0], 0.0, 1e-6);
}

// stress_response of the Model interface is the driver with the exponential scheme; the shear
// relaxation modulus (closed form) equals the response to a step and hold.
TEST(FritzsonPoint, ModelStressResponseAndRelaxation) {
  const auto model = make_model("fritzson", {{"reference_C", 23.0}});
  const std::vector<double> p = material1_parameters();
  const TestCondition c = condition(TestMode::shear, "23", 1.0, 40.0, 0.0, 0.0);
  StrainHistory h;
  for (int k = 0; k <= 50; ++k) {
    h.time_s.push_back(1e-4 * k * k);
    h.strain.push_back(1e-3);
  }
  const std::vector<double> s = model->stress_response(p.data(), c, h);
  for (size_t k = 0; k < s.size(); ++k)
    EXPECT_NEAR(s[k] / 1e-3, model->relaxation_modulus(p.data(), c, h.time_s[k]),
                1e-9 * s[0] / 1e-3);
  // Uniaxial relaxation: at t = 0 the instantaneous E = 9K M0/(3K + M0) (isotropic model).
  const auto iso = make_model("fritzson-iso", {{"reference_C", 23.0}});
  const std::vector<double> q = material2_parameters();
  const TestCondition u = condition(TestMode::uniaxial, "", 1.0, 23.0, 0.0, 0.0);
  const double M0 = q[kPartI + kMean] + 5 * q[kPartI + kBeta2] * q[kPartI + kViscous];
  EXPECT_NEAR(iso->relaxation_modulus(q.data(), u, 0.0), 9 * q[kK] * M0 / (3 * q[kK] + M0), 1e-6 * M0);
  const double late = iso->relaxation_modulus(q.data(), u, 100.0);
  const double M_inf = q[kPartI + kMean];
  EXPECT_NEAR(late, 9 * q[kK] * M_inf / (3 * q[kK] + M_inf), 1e-3 * M_inf);
}

}  // namespace
