// Hyperelastic laws (docs/hyperelastic.md): the closed-form nominal stress of every law in every
// mode against central differences of its strain energy W along the same deformation path (an
// independent route: W is coded apart from τ_i = λ_i ∂W/∂λ_i), and the Drucker check.
#include <gtest/gtest.h>

#include <cmath>
#include <Eigen/Eigenvalues>

#include "fitlib/core/error.hpp"
#include "fitlib/model/hyperelastic.hpp"
#include "fitlib/model/material_point.hpp"

using namespace fitlib::model;

namespace {

struct Case {
  std::string kind;
  nlohmann::json options;
  std::vector<double> p;  // without D1
};

std::vector<Case> cases() {
  return {{"neo-hooke", {}, {0.2}},
          {"mooney-rivlin", {{"terms", 2}}, {0.19, 0.02}},
          {"mooney-rivlin", {{"terms", 3}}, {0.19, 0.02, 0.003}},
          {"yeoh", {}, {0.19, -0.0016, 4.1e-5}},
          {"reduced-polynomial", {{"terms", 6}}, {0.19, -0.0016, 4.1e-5, 1e-6, 1e-8, 1e-10}},
          {"ogden", {{"terms", 1}}, {0.4, 2.5}},
          {"ogden", {{"terms", 3}}, {0.40352, 1.2559, 0.0069234, -2.2218, 0.0017588, 5.365}},
          {"ogden", {{"terms", 6}}, {0.3, 1.2, 0.01, -2.0, 0.002, 5.0, 0.05, 2.0, -0.001, -4.0, 0.02, 0.5}},
          {"arruda-boyce", {}, {0.3369, 5.272}},
          {"gent", {}, {0.3415, 110.9}}};
}

// Principal stretches of a deformation gradient (√ eigenvalues of FᵀF).
std::array<double, 3> stretches_of(const Eigen::Matrix3d& F) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(F.transpose() * F);
  const Eigen::Vector3d l = eig.eigenvalues().cwiseSqrt();
  return {l[0], l[1], l[2]};
}

// W along the mode's path at abscissa x; dW/dx = work_factor × P.
double path_energy(const HyperelasticLaw& law, const double* p, DeformationMode mode, double x) {
  switch (mode) {
    case DeformationMode::uniaxial: return law.energy(p, {x, 1.0 / std::sqrt(x), 1.0 / std::sqrt(x)});
    case DeformationMode::equibiaxial: return law.energy(p, {x, x, 1.0 / (x * x)});
    case DeformationMode::planar: return law.energy(p, {x, 1.0, 1.0 / x});
    case DeformationMode::simple_shear: {
      Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
      F(0, 1) = x;
      return law.energy(p, stretches_of(F));
    }
    case DeformationMode::volumetric: return law.energy(p, {std::cbrt(x), std::cbrt(x), std::cbrt(x)});
  }
  return 0.0;
}

// Nominal stress from the work: equibiaxial stretches both directions (dW = 2 P dλ); the
// pressure does negative work (dW = −p dJ).
double work_factor(DeformationMode mode) {
  return mode == DeformationMode::equibiaxial ? 2.0 : mode == DeformationMode::volumetric ? -1.0 : 1.0;
}

}  // namespace

TEST(Hyperelastic, NominalStressOfEveryLawInEveryModeIsTheDerivativeOfW) {
  for (bool compressible : {false, true}) {
    for (const auto& c : cases()) {
      nlohmann::json options = c.options.is_null() ? nlohmann::json::object() : c.options;
      options["compressible"] = compressible;
      const ModelPtr model = make_model(c.kind, options);
      const HyperelasticLaw* law = model->hyperelastic();
      ASSERT_NE(law, nullptr) << c.kind;
      std::vector<double> p = c.p;
      if (compressible) p.push_back(2.0 / 500.0);  // D1 = 2/K, K = 500 MPa
      ASSERT_EQ(p.size(), model->size()) << c.kind;
      std::vector<DeformationMode> modes = {DeformationMode::uniaxial, DeformationMode::equibiaxial,
                                            DeformationMode::planar, DeformationMode::simple_shear};
      if (compressible) modes.push_back(DeformationMode::volumetric);
      for (DeformationMode mode : modes) {
        const std::vector<double> xs = mode == DeformationMode::simple_shear ? std::vector<double>{-1.5, 0.05, 0.8, 2.5}
                                       : mode == DeformationMode::volumetric ? std::vector<double>{0.95, 0.999, 1.02}
                                                                             : std::vector<double>{0.4, 0.9, 1.3, 2.5, 5.0};
        for (double x : xs) {
          if (c.kind == "gent" && mode == DeformationMode::equibiaxial && x > 4.0) continue;  // locked
          const double h = 1e-5 * std::max(1.0, std::abs(x));
          const double dW = (path_energy(*law, p.data(), mode, x + h) - path_energy(*law, p.data(), mode, x - h)) / (2 * h);
          const double P = law->nominal_stress(p.data(), mode, x);
          EXPECT_NEAR(P, dW / work_factor(mode), 2e-6 * (1.0 + std::abs(P)))
              << c.kind << " " << to_string(mode) << " x " << x << " compressible " << compressible;
        }
      }
    }
  }
}

TEST(Hyperelastic, GradientMatchesFiniteDifferencesOfTheStress) {
  for (const auto& c : cases()) {
    const ModelPtr model = make_model(c.kind, c.options);
    const HyperelasticLaw& law = *model->hyperelastic();
    std::vector<double> g(model->size());
    const double P = law.nominal_stress(c.p.data(), DeformationMode::planar, 2.2, g.data());
    EXPECT_DOUBLE_EQ(P, law.nominal_stress(c.p.data(), DeformationMode::planar, 2.2));
    for (std::size_t i = 0; i < c.p.size(); ++i) {
      std::vector<double> a = c.p, b = c.p;
      const double h = 1e-6 * std::max(1.0, std::abs(c.p[i]));
      a[i] += h, b[i] -= h;
      const double fd = (law.nominal_stress(a.data(), DeformationMode::planar, 2.2) -
                         law.nominal_stress(b.data(), DeformationMode::planar, 2.2)) / (2 * h);
      EXPECT_NEAR(g[i], fd, 1e-5 * (1.0 + std::abs(fd))) << c.kind << " parameter " << i;
    }
  }
}

TEST(Hyperelastic, InitialShearModulusIsTheSmallStrainSlope) {
  // Simple shear: P12 ≈ μ0 γ for small γ, for every law.
  for (const auto& c : cases()) {
    const ModelPtr model = make_model(c.kind, c.options);
    const HyperelasticLaw& law = *model->hyperelastic();
    const double g = 1e-5;
    EXPECT_NEAR(law.nominal_stress(c.p.data(), DeformationMode::simple_shear, g) / g,
                law.initial_shear_modulus(c.p.data()), 1e-6) << c.kind;
    TestCondition shear;
    EXPECT_DOUBLE_EQ(model->moduli(c.p.data(), shear).storage, law.initial_shear_modulus(c.p.data()));
  }
}

TEST(Hyperelastic, NeoHookeClosedForms) {
  // P = 2 C10 (λ − λ^-2) uniaxial, 2 C10 (λ − λ^-5) equibiaxial, 2 C10 (λ − λ^-3) planar, σ12 = 2 C10 γ.
  const ModelPtr m = make_model("neo-hooke", {});
  const double p[] = {0.25};
  const HyperelasticLaw& law = *m->hyperelastic();
  const double l = 2.3;
  EXPECT_NEAR(law.nominal_stress(p, DeformationMode::uniaxial, l), 0.5 * (l - 1 / (l * l)), 1e-14);
  EXPECT_NEAR(law.nominal_stress(p, DeformationMode::equibiaxial, l), 0.5 * (l - std::pow(l, -5)), 1e-14);
  EXPECT_NEAR(law.nominal_stress(p, DeformationMode::planar, l), 0.5 * (l - std::pow(l, -3)), 1e-14);
  EXPECT_NEAR(law.nominal_stress(p, DeformationMode::simple_shear, 0.7), 0.5 * 0.7, 1e-13);
  EXPECT_NEAR(law.cauchy_stress(p, DeformationMode::uniaxial, l), 0.5 * (l * l - 1 / l), 1e-13);
}

TEST(Hyperelastic, DruckerCatchesAKnownUnstableSet) {
  // Mooney–Rivlin fitted to Treloar's uniaxial data alone, C10 = 0.2158, C01 = −0.06304
  // (datasets/materials/hyperelastic README reference fits): unstable in equibiaxial tension.
  const ModelPtr m = make_model("mooney-rivlin", {});
  const double bad[] = {0.2158, -0.06304}, good[] = {0.1937, 0.002809};
  const HyperelasticLaw& law = *m->hyperelastic();
  const double at = first_unstable_stretch(law, bad, DeformationMode::equibiaxial, 10.0);
  EXPECT_GT(at, 1.0);
  EXPECT_LT(at, 10.0);
  for (DeformationMode mode : {DeformationMode::uniaxial, DeformationMode::equibiaxial, DeformationMode::planar})
    for (double to : {10.0, 0.1}) EXPECT_EQ(first_unstable_stretch(law, good, mode, to), 0.0) << to_string(mode) << to;
}

TEST(Hyperelastic, OptionsAreChecked) {
  EXPECT_THROW(make_model("ogden", {{"terms", 7}}), fitlib::core::UsageError);
  EXPECT_THROW(make_model("yeoh", {{"terms", 3}}), fitlib::core::UsageError);
  EXPECT_THROW(make_model("gent", {{"bulk", true}}), fitlib::core::UsageError);
  const ModelPtr m = make_model("ogden", {{"terms", 2}, {"compressible", true}});
  EXPECT_EQ(m->size(), 5u);
  EXPECT_EQ(m->parameters().back().name, "D1");
  EXPECT_EQ(make_model(m->kind(), m->options())->size(), 5u);
  const double p[] = {0.2};
  EXPECT_THROW(make_model("neo-hooke", {})->hyperelastic()->nominal_stress(p, DeformationMode::volumetric, 0.9),
               fitlib::core::UsageError);
}

TEST(Hyperelastic, MaterialPointGivesTheUniaxialStressOfTheLaw) {
  // Nearly incompressible point (K = 10⁴ μ0) driven in uniaxial stress: τ11/λ = P of the law.
  for (const auto& c : cases()) {
    const ModelPtr model = make_model(c.kind, c.options);
    PointOptions o;
    o.bulk_modulus_MPa = 1e4 * model->hyperelastic()->initial_shear_modulus(c.p.data());
    const auto point = model->material_point(c.p.data(), o);
    DriveProgram prog;
    const double l = 1.8;
    prog.time_s = {0.0, 1.0, 2.0, 3.0, 4.0};
    prog.components[0].imposed = DriveControl::Imposed::strain;
    for (double t : prog.time_s) prog.components[0].values.push_back(std::log(1.0 + (l - 1.0) * t / 4.0));
    prog.stress_tolerance_MPa = 1e-12;
    const DriveResult r = drive(*point, prog);
    const Vector6 tau = r.stress.back();
    const double P = tau[0] / l;  // σ11 = τ11/J, P = σ11 · (area ratio J/λ) = τ11/λ
    const double expect = model->hyperelastic()->nominal_stress(c.p.data(), DeformationMode::uniaxial, l);
    EXPECT_NEAR(P, expect, 2e-3 * std::abs(expect)) << c.kind;
  }
}

TEST(ViscoHyperelastic, StepInSimpleShearRelaxesAsTheProny) {
  // A finite simple-shear step (γ = 1) held: τ_dev(t) = τ∞_dev g(t)/(1 − Σ g_i),
  // g(t) = 1 − Σ g_i (1 − e^(−t/τ_i)); the hydrostatic part stays elastic.
  const ModelPtr m = make_model("visco-hyperelastic", {{"base", "ogden"}, {"base_options", {{"terms", 2}}}, {"terms", 2}});
  const std::vector<double> p = {0.4, 1.5, 0.005, 5.0, 0.3, 0.2, 0.1, 10.0};
  PointOptions o;
  o.bulk_modulus_MPa = 1000.0;
  const auto point = m->material_point(p.data(), o);
  const auto base = make_model("ogden", {{"terms", 2}})->material_point(p.data(), o);
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 1) = 1.0;
  const Vector6 e = log_strain(F);
  std::vector<double> state = point->initial_state(), next(point->state_size());
  point->update(state.data(), e, 1e-12, NAN, next.data());
  state.swap(next);
  const Vector6 inf = base->update(nullptr, e, 0.0, NAN, nullptr);
  double t = 1e-12;
  for (double dt : {0.01, 0.04, 0.2, 0.75, 3.0, 6.0, 40.0}) {
    Matrix6 C;
    const Vector6 s = point->update(state.data(), e, dt, NAN, next.data(), &C);
    state.swap(next);
    t += dt;
    const double g = 1.0 - 0.3 * (1.0 - std::exp(-t / 0.1)) - 0.2 * (1.0 - std::exp(-t / 10.0));
    EXPECT_NEAR(s[5], inf[5] * g / 0.5, 1e-6 * std::abs(inf[5])) << "t " << t;
    EXPECT_NEAR(s.head<3>().sum(), inf.head<3>().sum(), 1e-9 * std::abs(inf[0]) + 1e-12) << "t " << t;
  }
  // Small-strain dynamic stiffness: G* of the Prony about μ0 = G∞ of the base.
  const auto C = point->complex_stiffness(1.0, NAN);
  TestCondition shear;
  shear.frequency_Hz = 1.0;
  EXPECT_NEAR(C(5, 5).real(), m->moduli(p.data(), shear).storage, 1e-12);
  EXPECT_NEAR(C(5, 5).imag(), m->moduli(p.data(), shear).loss, 1e-12);
  EXPECT_NEAR(m->relaxation_modulus(p.data(), shear, 1e6), 0.405, 1e-9);
}
