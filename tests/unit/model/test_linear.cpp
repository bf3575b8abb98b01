// Linear viscoelastic models: closed forms, Jacobians, time domain against the complex form.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"
#include "fitlib/model/linear.hpp"
#include "fitlib/model/time_series.hpp"

using namespace fitlib;
using model::TestCondition;
using model::TestMode;

namespace {

struct Case {
  std::string kind;
  nlohmann::json options;
  std::vector<double> p;
};

// One parameter set per kind, times spread over 1e-4 … 1e2 s around a 1 Hz test.
std::vector<Case> cases() {
  return {
      {"prony", {{"terms", 4}}, {2.0, 5.0, 3.0, 1.0, 0.5, 1e-4, 1e-2, 0.3, 100.0}},
      {"zener3", {}, {60000.0, 0.2, 0.3}},
      {"retardation", {{"terms", 3}}, {0.01, 0.05, 0.2, 0.1, 1e-3, 0.1, 20.0}},
      {"fractional-zener", {}, {1.5, 20.0, 0.05, 0.45}},
  };
}

TestCondition at(double f_Hz, TestMode mode = TestMode::shear) {
  TestCondition c;
  c.mode = mode;
  c.frequency_Hz = f_Hz;
  c.strain_amplitude = 0.01;
  return c;
}

}  // namespace

TEST(LinearModel, PronyOneTermIsTheMaxwellClosedForm) {
  auto m = model::make_model("prony", {{"terms", 1}});
  const double p[] = {2.0, 3.0, 0.1};  // G_inf, G_1, tau_1
  const double w = 2 * core::kPi * 5.0, wt = w * 0.1;
  const auto r = m->moduli(p, at(5.0));
  EXPECT_DOUBLE_EQ(r.storage, 2.0 + 3.0 * wt * wt / (1 + wt * wt));
  EXPECT_DOUBLE_EQ(r.loss, 3.0 * wt / (1 + wt * wt));
  EXPECT_DOUBLE_EQ(r.mean, 2.0);
  EXPECT_EQ(m->parameters()[0].name, "G_inf");
  EXPECT_EQ(m->parameters()[2].name, "tau_1");
}

TEST(LinearModel, Zener3MatchesItsPronyEquivalentAndIsElasticWhenTimesAreEqual) {
  auto z = model::make_model("zener3", {});
  auto p1 = model::make_model("prony", {{"terms", 1}});
  const double pz[] = {60000.0, 0.2, 0.3};
  const double pp[] = {60000.0, 60000.0 * (0.3 / 0.2 - 1.0), 0.2};
  for (double f : {0.01, 0.5, 3.0, 100.0}) {
    const auto a = z->moduli(pz, at(f)), b = p1->moduli(pp, at(f));
    EXPECT_NEAR(a.storage, b.storage, 1e-9 * b.storage);
    EXPECT_NEAR(a.loss, b.loss, 1e-9 * b.storage);
  }
  const double elastic[] = {500.0, 0.25, 0.25};
  const auto e = z->moduli(elastic, at(7.0));
  EXPECT_DOUBLE_EQ(e.storage, 500.0);
  EXPECT_DOUBLE_EQ(e.loss, 0.0);
}

TEST(LinearModel, RetardationIsTheInverseOfItsComplexCompliance) {
  auto m = model::make_model("retardation", {{"terms", 2}});
  const double p[] = {0.01, 0.05, 0.2, 0.1, 10.0};
  const double w = 2 * core::kPi * 0.7;
  std::complex<double> J = 0.01 + 0.05 / (1.0 + std::complex<double>(0, w * 0.1)) +
                           0.2 / (1.0 + std::complex<double>(0, w * 10.0));
  const auto M = 1.0 / J;
  const auto r = m->moduli(p, at(0.7));
  EXPECT_NEAR(r.storage, M.real(), 1e-12 * std::abs(M));
  EXPECT_NEAR(r.loss, M.imag(), 1e-12 * std::abs(M));
  EXPECT_NEAR(r.mean, 1.0 / 0.26, 1e-12);
}

TEST(LinearModel, FractionalZenerLimitsAndSpectrumQuadrature) {
  auto m = model::make_model("fractional-zener", {});
  const double p[] = {1.5, 20.0, 0.05, 0.45};
  EXPECT_NEAR(m->moduli(p, at(1e-12)).storage, 1.5, 1e-3);
  EXPECT_NEAR(m->moduli(p, at(1e12)).storage, 21.5, 1e-3);
  // The time-domain spectrum, as a Maxwell series, reproduces the closed form.
  auto prony = model::make_model("prony", {{"terms", 1}});
  model::MaxwellSeries s;
  ASSERT_FALSE(m->maxwell_series(p, &s));  // not exact: no FE export
  for (double f : {1e-3, 0.1, 3.0, 300.0}) {
    const double w = 2 * core::kPi * f;
    std::complex<double> z = std::pow(std::complex<double>(0, w * 0.05), 0.45);
    const auto exact = 1.5 + 20.0 * z / (1.0 + z);
    const auto r = m->moduli(p, at(f));
    EXPECT_NEAR(r.storage, exact.real(), 1e-12 * std::abs(exact));
    EXPECT_NEAR(r.loss, exact.imag(), 1e-12 * std::abs(exact));
  }
}

TEST(LinearModel, JacobianMatchesCentralDifferences) {
  for (const auto& cs : cases()) {
    nlohmann::json opt = cs.options;
    opt["temperature_law"] = "wlf";
    opt["reference_C"] = 20.0;
    opt["linear_factor"] = true;
    auto m = model::make_model(cs.kind, opt);
    std::vector<double> p = cs.p;
    p.push_back(8.0);    // C1
    p.push_back(120.0);  // C2
    p.push_back(0.004);  // c_T
    ASSERT_EQ(p.size(), m->size()) << cs.kind;
    TestCondition c = at(2.0);
    c.temperature_C = 45.0;
    // NaN first: every entry, the mean modulus's row included, is the model's to write (Prony's
    // closed form writes each one instead of zeroing the block first).
    Eigen::MatrixXd J = Eigen::MatrixXd::Constant(3, m->size(), std::nan(""));
    const auto v = m->moduli(p.data(), c, J);
    const auto plain = m->moduli(p.data(), c);
    EXPECT_DOUBLE_EQ(v.storage, plain.storage);
    for (size_t i = 0; i < p.size(); ++i) {
      auto hi = p, lo = p;
      const double h = 1e-6 * std::max(std::abs(p[i]), 1e-3);
      hi[i] += h;
      lo[i] -= h;
      const auto a = m->moduli(hi.data(), c), b = m->moduli(lo.data(), c);
      const double scale = std::abs(plain.storage) + std::abs(plain.loss);
      EXPECT_NEAR(J(0, i), (a.storage - b.storage) / (2 * h), 1e-5 * scale / std::max(std::abs(p[i]), 1e-3))
          << cs.kind << " d storage / d " << m->parameters()[i].name;
      EXPECT_NEAR(J(1, i), (a.loss - b.loss) / (2 * h), 1e-5 * scale / std::max(std::abs(p[i]), 1e-3))
          << cs.kind << " d loss / d " << m->parameters()[i].name;
      EXPECT_NEAR(J(2, i), (a.mean - b.mean) / (2 * h), 1e-5 * scale / std::max(std::abs(p[i]), 1e-3))
          << cs.kind << " d mean / d " << m->parameters()[i].name;
    }
  }
}

// Independent implementations: time integration of the strain history vs the complex form.
TEST(LinearModel, SteadyStateOfTimeIntegrationEqualsComplexForm) {
  for (const auto& cs : cases()) {
    for (bool shifted : {false, true}) {
      nlohmann::json opt = cs.options;
      std::vector<double> p = cs.p;
      TestCondition c = at(1.0);
      if (shifted) {
        opt["temperature_law"] = "wlf";
        opt["reference_C"] = 20.0;
        p.push_back(8.0);
        p.push_back(120.0);
        c.temperature_C = 30.0;
      }
      auto m = model::make_model(cs.kind, opt);
      const auto complex_form = m->moduli(p.data(), c);
      const auto stepped = model::steady_state_by_time_integration(*m, p.data(), c);
      const double scale = std::hypot(complex_form.storage, complex_form.loss);
      const double tol = cs.kind == "fractional-zener" ? 2e-6 : 1e-6;
      EXPECT_NEAR(stepped.storage, complex_form.storage, tol * scale) << cs.kind << " shifted " << shifted;
      EXPECT_NEAR(stepped.loss, complex_form.loss, tol * scale) << cs.kind << " shifted " << shifted;
    }
  }
}

TEST(LinearModel, CreepAndRelaxationAgainstClosedForms) {
  // Three-parameter solid: J(t) = (1/S)[1 − (1 − τ_T/τ_ε) e^{−t/τ_ε}] (stepped Maxwell creep).
  auto z = model::make_model("zener3", {});
  const double pz[] = {100.0, 0.2, 0.5};
  const TestCondition c = at(1.0);
  for (double t : {0.01, 0.3, 2.0}) {
    const double exact = (1.0 / 100.0) * (1.0 - (1.0 - 0.2 / 0.5) * std::exp(-t / 0.5));
    EXPECT_NEAR(z->creep_compliance(pz, c, t), exact, 1e-6 * exact) << t;
    EXPECT_NEAR(z->relaxation_modulus(pz, c, t), 100.0 * (1.0 + (0.5 / 0.2 - 1.0) * std::exp(-t / 0.2)), 1e-12);
  }
  // One Kelvin element = standard solid: M(t) = M_r + (M_g − M_r) e^{−t/τ}, τ = λ J_g/(J_g + L).
  auto r = model::make_model("retardation", {{"terms", 1}});
  const double pr[] = {0.01, 0.04, 2.0};
  const double Mg = 100.0, Mr = 20.0, tau = 2.0 * 0.01 / 0.05;
  for (double t : {0.05, 0.4, 3.0}) {
    const double exact = Mr + (Mg - Mr) * std::exp(-t / tau);
    EXPECT_NEAR(r->relaxation_modulus(pr, c, t), exact, 1e-5 * exact) << t;
    EXPECT_NEAR(r->creep_compliance(pr, c, t), 0.01 + 0.04 * (1 - std::exp(-t / 2.0)), 1e-15);
  }
}

TEST(LinearModel, FractionalRelaxationIsMittagLeffler) {
  auto m = model::make_model("fractional-zener", {});
  const double alpha = 0.6, p[] = {1.0, 9.0, 1.0, alpha};
  for (double t : {0.01, 0.1, 0.5}) {
    const double x = std::pow(t, alpha);
    double ml = 0.0, term_sign = 1.0;
    for (int k = 0; k < 80; ++k, term_sign = -term_sign)
      ml += term_sign * std::pow(x, k) / std::tgamma(alpha * k + 1.0);
    const double exact = 1.0 + 9.0 * ml;
    EXPECT_NEAR(m->relaxation_modulus(p, at(1.0), t), exact, 1e-4 * exact) << t;
  }
}

TEST(LinearModel, ModeConversionThroughBulkModulus) {
  auto m = model::make_model("prony", {{"terms", 1}, {"bulk_modulus", true}});
  const double K = 2000.0, p[] = {1.0, 2.0, 0.1, K};
  const auto g = m->moduli(p, at(1.0, TestMode::shear));
  const auto e = m->moduli(p, at(1.0, TestMode::uniaxial));
  const std::complex<double> G(g.storage, g.loss), E = 9.0 * K * G / (3.0 * K + G);
  EXPECT_NEAR(e.storage, E.real(), 1e-12 * std::abs(E));
  EXPECT_NEAR(e.loss, E.imag(), 1e-12 * std::abs(E));
  EXPECT_NEAR(e.storage / g.storage, 3.0, 2e-3);  // nearly incompressible: E ≈ 3G
  EXPECT_DOUBLE_EQ(m->moduli(p, at(1.0, TestMode::bulk)).storage, K);
  // Without a bulk modulus a card answers only its own mode.
  auto plain = model::make_model("prony", {{"terms", 1}});
  EXPECT_THROW(plain->moduli(p, at(1.0, TestMode::uniaxial)), core::UsageError);
}

TEST(LinearModel, WlfShiftIsAFrequencyShiftAndItsPoleIsAnError) {
  auto m = model::make_model("prony", {{"terms", 2}, {"temperature_law", "wlf"}, {"reference_C", 0.0}});
  const double p[] = {1.0, 5.0, 2.0, 0.01, 1.0, 10.0, 50.0};  // C1 = 10, C2 = 50 K
  TestCondition hot = at(2.0);
  hot.temperature_C = 25.0;
  const double aT = std::pow(10.0, -10.0 * 25.0 / (50.0 + 25.0));
  const auto shifted = m->moduli(p, hot);
  const auto reference = m->moduli(p, at(2.0 * aT));
  EXPECT_NEAR(shifted.storage, reference.storage, 1e-12 * reference.storage);
  EXPECT_NEAR(shifted.loss, reference.loss, 1e-12 * reference.storage);
  TestCondition beyond = at(1.0);
  beyond.temperature_C = -60.0;  // T − T_ref = −60 < −C2
  EXPECT_THROW(m->moduli(p, beyond), core::InputError);
}

TEST(LinearModel, OptionsAreValidated) {
  EXPECT_THROW(model::make_model("prony", {{"terms", 0}}), core::UsageError);
  EXPECT_THROW(model::make_model("prony", {{"colour", "red"}}), core::UsageError);
  EXPECT_THROW(model::make_model("prony", {{"temperature_law", "magic"}}), core::UsageError);
  EXPECT_THROW(model::make_model("maxwell-x", {}), core::UsageError);
  auto m = model::make_model("prony", {{"terms", 3}, {"mode", "uniaxial"}});
  EXPECT_EQ(m->parameters()[0].name, "E_inf");
  EXPECT_EQ(model::make_model(m->kind(), m->options())->options(), m->options());
}

// The temperature law has no material at or beyond the WLF pole (T_ref − C2) and where the linear
// factor g = 1 − c_T (T − T_ref) reaches its floor 10⁻³: T_ref + 0.999/c_T.
TEST(LinearModel, TemperatureLawEndsAtTheWlfPoleAndWhereTheLinearFactorVanishes) {
  nlohmann::json opt = {{"terms", 1}, {"temperature_law", "wlf"}, {"reference_C", 20.0}, {"linear_factor", true}};
  const auto m = model::make_model("prony", opt);
  std::vector<double> p = {1.0, 2.0, 0.1, 8.0, 120.0, 0.004};  // E∞, E1, τ1, C1, C2, c_T
  ASSERT_EQ(p.size(), m->size());
  for (double T : {-99.9, 20.0, 269.7}) EXPECT_EQ(m->temperature_out_of_law(p.data(), T), "") << T;
  EXPECT_EQ(m->temperature_out_of_law(p.data(), std::nan("")), "");  // NaN: the reference, as Model says
  EXPECT_NE(m->temperature_out_of_law(p.data(), -100.0).find("pole at T_ref - C2 = -100 degC"), std::string::npos);
  const std::string hot = m->temperature_out_of_law(p.data(), 269.8);  // 20 + 0.999/0.004 = 269.75
  EXPECT_NE(hot.find("c_T"), std::string::npos) << hot;
  EXPECT_NE(hot.find("below 269.75 degC"), std::string::npos) << hot;
  EXPECT_EQ(model::make_model("prony", {{"terms", 1}})->temperature_out_of_law(p.data(), 1e3), "");
}
