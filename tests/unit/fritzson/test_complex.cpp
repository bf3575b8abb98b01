// Complex (steady sinusoidal) form of Fritzson's model: specs, damage and temperature functions,
// closed forms against independent derivations, Jacobians against central differences, the
// decisions on the spec's [UNCLEAR] points, and numerically hard inputs.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "fitlib/core/error.hpp"
#include "fitlib/model/fritzson.hpp"
#include "materials.hpp"
#include "fitlib/core/units.hpp"

namespace {

using namespace fitlib::model;
using namespace fitlib::model::fritzson;
using fritzson_test::material1_parameters;
using fritzson_test::material2_parameters;

using fitlib::core::kPi;

ModelPtr model1() { return make_model("fritzson", {{"reference_C", 23.0}}); }
ModelPtr model2() { return make_model("fritzson-iso", {{"reference_C", 23.0}}); }

TestCondition condition(TestMode mode, const std::string& orientation, double f, double T,
                        double amplitude) {
  TestCondition c;
  c.mode = mode;
  c.orientation = orientation;
  c.frequency_Hz = f;
  c.temperature_C = T;
  c.strain_amplitude = amplitude;
  c.mean_strain = amplitude;
  return c;
}

// The seven test types of the issue: shear 12, 13, 23; uniaxial 11, 22, 33; bulk.
std::vector<TestCondition> seven_tests(double T) {
  return {condition(TestMode::shear, "12", 10.0, T, 0.02),
          condition(TestMode::shear, "13", 10.0, T, 0.02),
          condition(TestMode::shear, "23", 10.0, T, 0.02),
          condition(TestMode::uniaxial, "11", 10.0, T, 0.01),
          condition(TestMode::uniaxial, "22", 10.0, T, 0.01),
          condition(TestMode::uniaxial, "33", 10.0, T, 0.005),
          condition(TestMode::bulk, "", 1.0, T, 0.001)};
}

TEST(FritzsonSpecs, CountsNamesGroupsBoundsAndTransforms) {
  const auto a = model1(), i = model2();
  EXPECT_EQ(a->size(), 38u);
  EXPECT_EQ(i->size(), 14u);
  EXPECT_EQ(a->kind(), "fritzson");
  EXPECT_EQ(i->kind(), "fritzson-iso");
  const std::set<std::string> groups = {"volumetric", "mean", "dynamic", "viscous",
                                        "damage", "temperature", "A1", "A2"};
  std::set<std::string> names;
  for (const auto& s : a->parameters()) {
    EXPECT_TRUE(names.insert(s.name).second) << s.name;
    EXPECT_TRUE(groups.count(s.group)) << s.name << " " << s.group;
    EXPECT_LE(s.lower, s.default_value) << s.name;
    EXPECT_GE(s.upper, s.default_value) << s.name;
    if (s.transform == fitlib::core::Transform::log) {
      EXPECT_GT(s.lower, 0.0) << s.name;
    }
    EXPECT_FALSE(s.unit.empty()) << s.name;
  }
  // The isotropic model is the first 14 parameters of the anisotropic one.
  for (size_t k = 0; k < i->size(); ++k) EXPECT_EQ(i->parameters()[k].name, a->parameters()[k].name);
  EXPECT_EQ(a->parameters()[kK].name, "K");
  EXPECT_EQ(a->parameters()[kCd].name, "C_d");
  EXPECT_EQ(a->parameters()[kPartA1 + kMean].name, "C33_Am");
  EXPECT_EQ(a->parameters()[kPartA2 + kC2].name, "c2_A2");
  EXPECT_EQ(a->parameters()[kPartI + kTau].transform, fitlib::core::Transform::log);
}

TEST(FritzsonSpecs, RegistryOptionsRoundTripAndErrors) {
  const auto m = make_model("fritzson", {{"reference_C", 40.0}});
  EXPECT_DOUBLE_EQ(m->options().at("reference_C").get<double>(), 40.0);
  const auto again = make_model(m->kind(), m->options());
  EXPECT_EQ(again->options(), m->options());
  EXPECT_TRUE(m->amplitude_dependent());
  EXPECT_THROW(make_model("fritzson", {{"reference_temperature", 40.0}}), fitlib::core::UsageError);
  // The fitter's generic options are accepted where the model has them built in.
  EXPECT_NO_THROW(make_model("fritzson-iso", {{"mode", "uniaxial"}, {"temperature_law", "none"},
                                              {"bulk_modulus", true}, {"reference_C", 23.0}}));
  EXPECT_THROW(make_model("fritzson", {{"temperature_law", "wlf"}}), fitlib::core::UsageError);
  const auto kinds = model_kinds();
  EXPECT_NE(std::find(kinds.begin(), kinds.end(), "fritzson-iso"), kinds.end());
}

TEST(FritzsonDamage, H1LimitsMidpointAndPolyaAccuracy) {
  const double beta = 0.3, alpha = 0.5, mu = -2.0;
  EXPECT_DOUBLE_EQ(damage_h1(0.0, beta, alpha, mu), 1.0);               // log guard
  EXPECT_NEAR(damage_h1(1e-12, beta, alpha, mu), 1.0, 1e-12);
  EXPECT_NEAR(damage_h1(1.0, beta, alpha, mu), beta, 1e-4);             // 4 α above μ
  EXPECT_DOUBLE_EQ(damage_h1(0.01, beta, alpha, mu), 0.5 * (1.0 + beta));  // sgn(0) = 0
  // Pólya's approximation of the normal CDF: |error| < 0.0032 (1 − Φ(y) = ½ erfc(y/√2)).
  for (double y = -4.0; y <= 4.0; y += 0.05) {
    const double driver = std::pow(10.0, mu + alpha * y);
    const double exact = beta + (1.0 - beta) * 0.5 * std::erfc(y / std::sqrt(2.0));
    EXPECT_NEAR(damage_h1(driver, beta, alpha, mu), exact, 0.0032 * (1.0 - beta)) << y;
  }
}

TEST(FritzsonDamage, DerivativeAtTheMidpointIsFinite) {
  // At y = 0 the printed form has √0 and sgn(0); the analytic rewrite gives the exact slope
  // ∂h1/∂μ = ½(1 − β)√(2/π)/α there.
  using Jet = ceres::Jet<double, 1>;
  const Jet mu(-2.0, 0);
  const Jet h = damage_h1(0.01, Jet(0.3), Jet(0.5), mu);
  const double expected_dh_dmu = 0.5 * 0.7 * std::sqrt(2.0 / kPi) / 0.5;
  EXPECT_TRUE(std::isfinite(h.v[0]));
  EXPECT_NEAR(h.v[0], expected_dh_dmu, 1e-12);
}

TEST(FritzsonDamage, H2IsAGaussianInLogStrainWithPeakOne) {
  const double beta2 = 0.4, alpha2 = 0.5, mu = -2.0;
  EXPECT_DOUBLE_EQ(damage_h2(0.01, beta2, alpha2, mu), 1.0);
  EXPECT_DOUBLE_EQ(damage_h2(0.0, beta2, alpha2, mu), beta2);
  EXPECT_NEAR(damage_h2(0.1, beta2, alpha2, mu), beta2 + (1 - beta2) * std::exp(-2.0), 1e-14);
  EXPECT_NEAR(damage_h2(0.1, beta2, alpha2, mu), damage_h2(0.001, beta2, alpha2, mu), 1e-14);
}

TEST(FritzsonTemperature, LinearFactorReferenceAndFloor) {
  EXPECT_DOUBLE_EQ(temperature_factor(0.006, 23.0, 23.0), 1.0);
  EXPECT_DOUBLE_EQ(temperature_factor(0.006, std::nan(""), 23.0), 1.0);
  EXPECT_NEAR(temperature_factor(0.006, 100.0, 23.0), 1.0 - 0.006 * 77.0, 1e-15);
  EXPECT_DOUBLE_EQ(temperature_factor(0.02, 150.0, 23.0), kTemperatureFloor);
}

// Small amplitude (h1 = 1, h2 = β2), k = 1 (five equal Maxwell elements): closed form.
TEST(FritzsonComplex, ShearClosedFormWithEqualRelaxationTimes) {
  std::vector<double> p = material1_parameters();
  p[kPartI + kK_ratio] = 1.0;
  p[kPartA2 + kK_ratio] = 1.0;
  const auto m = model1();
  const double f = 20.0, T = 60.0, w = 2 * kPi * f;
  auto part = [&](int o) {
    const double g1 = 1 - p[o + kC1] * (T - 23), g2 = 1 - p[o + kC2] * (T - 23);
    const double x = w * p[o + kTau];
    const double v = 5 * p[o + kBeta2] * g2 * p[o + kViscous];
    return std::array<double, 3>{g1 * (p[o + kMean] + p[o + kDynamic]) + v * x * x / (1 + x * x),
                                 v * x / (1 + x * x), g1 * p[o + kMean]};
  };
  const auto i = part(kPartI), a2 = part(kPartA2);
  for (const char* o : {"12", "21"}) {
    const auto r = m->moduli(p.data(), condition(TestMode::shear, o, f, T, 0.0));
    EXPECT_NEAR(r.storage, i[0], 1e-12);
    EXPECT_NEAR(r.loss, i[1], 1e-12);
    EXPECT_NEAR(r.mean, i[2], 1e-12);
  }
  for (const char* o : {"13", "23", "32"}) {
    const auto r = m->moduli(p.data(), condition(TestMode::shear, o, f, T, 0.0));
    EXPECT_NEAR(r.storage, i[0] + a2[0], 1e-12);
    EXPECT_NEAR(r.loss, i[1] + a2[1], 1e-12);
    EXPECT_NEAR(r.mean, i[2] + a2[2], 1e-12);
  }
}

// Uniaxial moduli against the inverse of the full complex stiffness assembled from the printed
// equations (4.39–4.84): σ = K tr ε + 2M_I e + A1 (s3 = 2M_A1 e3 spread −½, −½, 1).
TEST(FritzsonComplex, UniaxialAgainstInverseOfAssembledStiffness) {
  const auto m = model1();
  const std::vector<double> p = material1_parameters();
  for (double K : {4000.0, 40.0}) {
    std::vector<double> q = p;
    q[kK] = K;
    const double f = 34.0, T = 23.0;
    // Amplitude 0: h1 = 1, h2 = β2, so the part moduli are those of the closed form.
    auto part = [&](int o) {
      std::complex<double> s(0, 0);
      double times[5];
      maxwell_times(q[o + kTau], q[o + kK_ratio], times);
      for (double tau : times) {
        const std::complex<double> iwt(0.0, 2 * kPi * f * tau);
        s += iwt / (1.0 + iwt);
      }
      return q[o + kMean] + q[o + kDynamic] + q[o + kBeta2] * q[o + kViscous] * s;
    };
    const std::complex<double> MI = part(kPartI), MA = part(kPartA1);
    Eigen::Matrix3cd C;
    const Eigen::RowVector3d de3(-1.0 / 3, -1.0 / 3, 2.0 / 3);  // ∂e3/∂ε
    const Eigen::Vector3d spread(-0.5, -0.5, 1.0);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        C(r, c) = K + 2.0 * MI * ((r == c ? 1.0 : 0.0) - 1.0 / 3) + 2.0 * MA * spread[r] * de3[c];
    const Eigen::Matrix3cd S = C.inverse();
    for (int axis = 0; axis < 3; ++axis) {
      const std::string o(2, char('1' + axis));
      const auto r = m->moduli(q.data(), condition(TestMode::uniaxial, o, f, T, 0.0));
      const std::complex<double> E = 1.0 / S(axis, axis);
      EXPECT_NEAR(r.storage, E.real(), 1e-9 * std::abs(E)) << o << " K=" << K;
      EXPECT_NEAR(r.loss, E.imag(), 1e-9 * std::abs(E)) << o << " K=" << K;
    }
  }
}

TEST(FritzsonComplex, IncompressibleLimitsOfTheSpec) {
  // constitutive-model.md §7: E33 = 3(G + C'), E22 = 12G(G + C')/(4G + 3C') for K → ∞.
  std::vector<double> p = material1_parameters();
  p[kK] = 1e12;
  const auto m = model1();
  const auto s12 = m->moduli(p.data(), condition(TestMode::shear, "12", 3.0, 23.0, 0.0));
  // C'33 static part: the mean modulus of A1 at zero amplitude is C33_Am.
  const double G = s12.mean, Cp = p[kPartA1 + kMean];
  const auto u33 = m->moduli(p.data(), condition(TestMode::uniaxial, "33", 3.0, 23.0, 0.0));
  const auto u22 = m->moduli(p.data(), condition(TestMode::uniaxial, "22", 3.0, 23.0, 0.0));
  EXPECT_NEAR(u33.mean, 3 * (G + Cp), 1e-9 * u33.mean);
  EXPECT_NEAR(u22.mean, 12 * G * (G + Cp) / (4 * G + 3 * Cp), 1e-9 * u22.mean);
}

TEST(FritzsonComplex, IsotropicModelUniaxialAndBulk) {
  const auto m = model2();
  const std::vector<double> p = material2_parameters();
  const auto g = m->moduli(p.data(), condition(TestMode::shear, "13", 34.0, 60.0, 0.0));
  const auto e = m->moduli(p.data(), condition(TestMode::uniaxial, "", 34.0, 60.0, 0.0));
  const std::complex<double> G(g.storage, g.loss), K = p[kK];
  const std::complex<double> E = 9.0 * K * G / (3.0 * K + G);
  EXPECT_NEAR(e.storage, E.real(), 1e-10 * std::abs(E));
  EXPECT_NEAR(e.loss, E.imag(), 1e-10 * std::abs(E));
  EXPECT_NEAR(e.mean, 9 * p[kK] * g.mean / (3 * p[kK] + g.mean), 1e-10 * e.mean);
  const auto b = m->moduli(p.data(), condition(TestMode::bulk, "", 1.0, 100.0, 0.002));
  EXPECT_DOUBLE_EQ(b.storage, p[kK]);  // purely elastic, no damage, no temperature (L2224)
  EXPECT_DOUBLE_EQ(b.loss, 0.0);
  EXPECT_DOUBLE_EQ(b.mean, p[kK]);
}

TEST(FritzsonComplex, SteadyDamageDriversPerTestType) {
  // Shear γ_a → e^o = γ_a/√2 (spec §7): the I part of shear 12 equals the undamaged form with
  // h1, h2 evaluated at γ_a/√2.
  const auto m = model1();
  const std::vector<double> p = material1_parameters();
  const double gamma = 0.03;
  const auto r = m->moduli(p.data(), condition(TestMode::shear, "12", 3.0, 23.0, gamma));
  const double* I = p.data() + kPartI;
  const double h1 = damage_h1(gamma / std::sqrt(2.0), I[kBeta1], I[kAlpha1], I[kMu]);
  EXPECT_NEAR(r.mean, h1 * I[kMean], 1e-12);
  // Uniaxial 33, near-incompressible: e^o_A1 = √2 ε_a, e^o_I = √1.5 ε_a.
  std::vector<double> q = p;
  q[kK] = 1e12;
  const double eps = 0.004;
  const auto u = m->moduli(q.data(), condition(TestMode::uniaxial, "33", 3.0, 23.0, eps));
  const double* A = q.data() + kPartA1;
  const double hI = damage_h1(std::sqrt(1.5) * eps, I[kBeta1], I[kAlpha1], I[kMu]);
  const double hA = damage_h1(std::sqrt(2.0) * eps, A[kBeta1], A[kAlpha1], A[kMu]);
  EXPECT_NEAR(u.mean, 3.0 * (hI * I[kMean] + hA * A[kMean]), 1e-7 * u.mean);
}

TEST(FritzsonComplex, JacobianMatchesCentralDifferencesForAllSevenTests) {
  for (int material : {1, 2}) {
    const auto m = material == 1 ? model1() : model2();
    const std::vector<double> p = material == 1 ? material1_parameters() : material2_parameters();
    for (const TestCondition& c : seven_tests(60.0)) {
      Eigen::MatrixXd J(3, m->size());
      const auto value = m->moduli(p.data(), c, J);
      const auto plain = m->moduli(p.data(), c);
      EXPECT_DOUBLE_EQ(value.storage, plain.storage);
      EXPECT_DOUBLE_EQ(value.loss, plain.loss);
      for (size_t k = 0; k < m->size(); ++k) {
        const double h = 1e-6 * std::max(std::abs(p[k]), 1e-2);
        std::vector<double> up = p, down = p;
        up[k] += h;
        down[k] -= h;
        const auto a = m->moduli(up.data(), c), b = m->moduli(down.data(), c);
        const double fd[3] = {(a.storage - b.storage) / (2 * h), (a.loss - b.loss) / (2 * h),
                              (a.mean - b.mean) / (2 * h)};
        const double scale[3] = {plain.storage, std::max(plain.loss, 1e-3 * plain.storage),
                                 plain.mean};
        for (int r = 0; r < 3; ++r)
          EXPECT_NEAR(J(r, k), fd[r], 1e-6 * scale[r] / std::max(std::abs(p[k]), 1e-2))
              << "material " << material << " " << to_string(c.mode) << " " << c.orientation
              << " row " << r << " " << m->parameters()[k].name;
      }
    }
  }
}

TEST(FritzsonComplex, OrientationDecisions) {
  const auto a = model1(), i = model2();
  const std::vector<double> p = material1_parameters(), q = material2_parameters();
  EXPECT_THROW(a->moduli(p.data(), condition(TestMode::shear, "", 3, 23, 0.01)),
               fitlib::core::UsageError);
  EXPECT_THROW(a->moduli(p.data(), condition(TestMode::shear, "22", 3, 23, 0.01)),
               fitlib::core::UsageError);
  EXPECT_THROW(a->moduli(p.data(), condition(TestMode::uniaxial, "23", 3, 23, 0.01)),
               fitlib::core::UsageError);
  EXPECT_THROW(a->moduli(p.data(), condition(TestMode::shear, "3232", 3, 23, 0.01)),
               fitlib::core::UsageError);
  // The isotropic model accepts any orientation (and none) with the same result.
  const auto none = i->moduli(q.data(), condition(TestMode::shear, "", 3, 23, 0.01));
  const auto o23 = i->moduli(q.data(), condition(TestMode::shear, "23", 3, 23, 0.01));
  EXPECT_DOUBLE_EQ(none.storage, o23.storage);
  // Transverse isotropy: 11 and 22 are the same.
  const auto u11 = a->moduli(p.data(), condition(TestMode::uniaxial, "11", 3, 60, 0.01));
  const auto u22 = a->moduli(p.data(), condition(TestMode::uniaxial, "22", 3, 60, 0.01));
  EXPECT_NEAR(u11.storage, u22.storage, 1e-12 * u22.storage);
  EXPECT_NEAR(u11.loss, u22.loss, 1e-12 * u22.storage);
}

TEST(FritzsonHardCases, AmplitudesFrom1e4To0p3AndZero) {
  const auto m = model1();
  const std::vector<double> p = material1_parameters();
  for (const TestCondition& base : seven_tests(23.0)) {
    TestCondition c = base;
    c.strain_amplitude = 0.0;
    const auto zero = m->moduli(p.data(), c);
    c.strain_amplitude = 1e-300;
    const auto tiny = m->moduli(p.data(), c);
    EXPECT_NEAR(tiny.storage, zero.storage, 1e-12 * zero.storage);
    for (double a : {1e-4, 1e-3, 0.01, 0.1, 0.3}) {
      c.strain_amplitude = a;
      Eigen::MatrixXd J(3, m->size());
      const auto r = m->moduli(p.data(), c, J);
      EXPECT_TRUE(std::isfinite(r.storage) && r.storage > 0) << a;
      EXPECT_TRUE(std::isfinite(r.loss) && r.loss >= 0) << a;
      EXPECT_TRUE(J.allFinite()) << a;
      EXPECT_LE(r.mean, zero.mean * (1 + 1e-12)) << a;  // h1 only softens the elastic parts
    }
    c.strain_amplitude = 1e-4;
    EXPECT_NEAR(m->moduli(p.data(), c).storage, zero.storage, 0.01 * zero.storage);
  }
}

TEST(FritzsonHardCases, BulkToShearRatiosFrom1e3To1e6) {
  const auto m = model2();
  std::vector<double> p = material2_parameters();
  const double G = p[kPartI + kMean];
  for (double ratio : {1e3, 1e4, 1e5, 1e6}) {
    p[kK] = ratio * G;
    const auto e = m->moduli(p.data(), condition(TestMode::uniaxial, "22", 3, 23, 0.0));
    EXPECT_NEAR(e.mean, 9 * p[kK] * G / (3 * p[kK] + G), 1e-12 * e.mean) << ratio;
    Eigen::MatrixXd J(3, m->size());
    m->moduli(p.data(), condition(TestMode::uniaxial, "33", 3, 23, 0.02), J);
    EXPECT_TRUE(J.allFinite());
  }
}

TEST(FritzsonModel, CreepComplianceIsRefusedWithAReason) {
  const auto m = model1();
  const std::vector<double> p = material1_parameters();
  try {
    m->creep_compliance(p.data(), condition(TestMode::shear, "12", 1, 23, 0), 1.0);
    FAIL() << "expected UsageError";
  } catch (const fitlib::core::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("path dependent"), std::string::npos);
  }
}

}  // namespace

namespace {

TEST(FritzsonModel, InitialParametersAreInsideTheBoundsAndPlacedFromTheData) {
  fitlib::model::DataSummary d;
  d.omega_min_rad_s = 2 * kPi * 3;
  d.omega_max_rad_s = 2 * kPi * 60;
  d.storage_min_MPa = 1.0;
  d.storage_max_MPa = 50.0;
  d.loss_max_MPa = 4.0;
  for (const auto& m : {model1(), model2()}) {
    const auto p = m->initial_parameters(d);
    ASSERT_EQ(p.size(), m->size());
    for (size_t k = 0; k < p.size(); ++k) {
      EXPECT_GE(p[k], m->parameters()[k].lower) << m->parameters()[k].name;
      EXPECT_LE(p[k], m->parameters()[k].upper) << m->parameters()[k].name;
    }
    EXPECT_NEAR(p[kPartI + kTau], 1.0 / std::sqrt(d.omega_min_rad_s * d.omega_max_rad_s), 1e-15);
  }
}

}  // namespace

namespace {

// Anywhere inside the bounds (and on them) the moduli and Jacobians are finite: what a fitter
// that walks to the bounds needs. Includes the far tail of h1 (β1 at its floor, μ = −5, α = 0.05).
TEST(FritzsonHardCases, FiniteEverywhereInsideTheBounds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const auto& m : {model1(), model2()}) {
    const auto& specs = m->parameters();
    for (int trial = 0; trial < 150; ++trial) {
      std::vector<double> p(specs.size());
      for (size_t k = 0; k < p.size(); ++k) {
        double x = u(rng);
        if (trial % 3 == 0) x = x < 0.5 ? 0.0 : 1.0;
        const auto& s = specs[k];
        p[k] = s.transform == fitlib::core::Transform::log
                   ? std::exp(std::log(s.lower) + x * (std::log(s.upper) - std::log(s.lower)))
                   : s.lower + x * (s.upper - s.lower);
      }
      for (const TestCondition& c : seven_tests(100.0)) {
        Eigen::MatrixXd J(3, m->size());
        const auto v = m->moduli(p.data(), c, J);
        ASSERT_TRUE(std::isfinite(v.storage) && std::isfinite(v.loss) && std::isfinite(v.mean) &&
                    J.allFinite())
            << m->kind() << " trial " << trial << " " << to_string(c.mode) << " " << c.orientation;
        EXPECT_GT(v.mean, 0.0);
      }
    }
  }
  // h1's upper tail stays above β1: 1 − Φ(8) ≈ 6e-16 would cancel to 0 in the printed form.
  EXPECT_GT(damage_h1(1e2, 0.0, 0.5, -2.0), 0.0);
  EXPECT_LT(damage_h1(1e2, 0.0, 0.5, -2.0), 1e-14);
}

}  // namespace

// Where a part's linear factor g = 1 − c (T − T_ref) reaches its floor the law describes no
// material: material 1's tightest constant is c2 = 0.008 /°C (c2_I, c2_A1, c2_A2), so its law ends
// at 23 + 0.999/0.008 = 147.875 °C, and the reason names that constant and limit. A negative
// constant bounds the law from below instead.
TEST(FritzsonTemperature, LawEndsWhereTheTightestLinearFactorReachesItsFloor) {
  const auto m = model1();
  std::vector<double> p = material1_parameters();
  for (double T : {std::nan(""), -273.15, 23.0, 147.87}) EXPECT_EQ(m->temperature_out_of_law(p.data(), T), "") << T;
  for (double T : {147.88, 200.0}) {
    const std::string why = m->temperature_out_of_law(p.data(), T);
    EXPECT_NE(why.find("c2_I"), std::string::npos) << why;
    EXPECT_NE(why.find("below 147.88 degC"), std::string::npos) << why;
  }
  p[kPartA2 + kC1] = -0.02;  // g rises with T: the law ends below 23 − 0.999/0.02 = −26.95 °C
  EXPECT_EQ(m->temperature_out_of_law(p.data(), -26.9), "");
  const std::string cold = m->temperature_out_of_law(p.data(), -27.0);
  EXPECT_NE(cold.find("c1_A2"), std::string::npos) << cold;
  EXPECT_NE(cold.find("above -26.95 degC"), std::string::npos) << cold;
  const auto iso = model2();  // only part I counts
  EXPECT_EQ(iso->temperature_out_of_law(material2_parameters().data(), 100.0), "");
}
