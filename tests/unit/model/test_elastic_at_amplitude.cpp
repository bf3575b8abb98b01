// The elastic equivalent at a stated strain amplitude (model::PointOptions::strain_amplitude;
// docs/model.md "Elastic equivalent at an amplitude"): Fritzson's storage stiffness at the damage
// drivers of the oscillation against the closed form of (4.35), (4.36) and the five-element
// Maxwell group, against the model's own test moduli, the hold, and the models that ignore it.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/model.hpp"

namespace {

using namespace fitlib::model;

// fritzson-iso: K, G_Im, G_Id, G_Iv, tau, k, beta1, alpha1, mu, beta2, alpha2, c1, c2, C_d.
const std::vector<double> kIso{4000.0, 2.5, 2.0, 0.21, 0.008, 2.5, 0.25, 0.6, -2.0, 0.5, 0.5, 0.0065, 0.008, 0.6};

Matrix6 stiffness_of(const MaterialPoint& point) {
  std::vector<double> none(point.state_size()), next(point.state_size());
  Matrix6 C;
  point.update(none.data(), Vector6::Zero(), 0.0, NAN, next.data(), &C);
  return C;
}

PointOptions elastic_at(double f_Hz, double T_C, std::optional<Vector6> amplitude) {
  PointOptions o;
  o.fidelity = fitlib::core::Fidelity::elastic;
  o.frequency_Hz = f_Hz, o.temperature_C = T_C, o.strain_amplitude = amplitude;
  return o;
}

Vector6 shear_amplitude(double gamma) {
  Vector6 a = Vector6::Zero();
  a[5] = gamma;
  return a;
}

// At the driver 10^μ the Pólya complement is ½ (h1 = (1 + β1)/2) and the Gaussian is at its peak
// (h2 = 1), so G' = (1 + β1)/2 g1 (G_m + G_d) + g2 G_v Σ (ωτ_n)²/(1 + (ωτ_n)²) (4.35, 4.36, 4.44–4.48).
TEST(ElasticAtAmplitude, FritzsonShearStorageModulusAtTheDriverMuIsTheClosedForm) {
  const auto model = make_model("fritzson-iso", {{"reference_C", 23.0}});
  const double f = 34.0, T = 60.0;
  const double gamma = std::sqrt(2.0) * std::pow(10.0, kIso[8]);  // driver γ/√2 = 10^μ
  const Matrix6 C = stiffness_of(*make_material_point(*model, kIso, elastic_at(f, T, shear_amplitude(gamma))));
  const double g1 = 1.0 - kIso[11] * (T - 23.0), g2 = 1.0 - kIso[12] * (T - 23.0);
  const double omega = 2.0 * M_PI * f, tau = kIso[4], k = kIso[5];
  double group = 0.0;
  for (double t : {tau, tau * k, tau / k, tau * k * k, tau / (k * k)}) group += (omega * t) * (omega * t) / (1.0 + (omega * t) * (omega * t));
  const double expected = 0.5 * (1.0 + kIso[6]) * g1 * (kIso[1] + kIso[2]) + g2 * kIso[3] * group;
  EXPECT_NEAR(C(5, 5), expected, 1e-12 * expected);
  EXPECT_NEAR(C(0, 0) - C(0, 1), 2.0 * expected, 1e-9 * expected);  // isotropic: the same G in every mode
  // The small-amplitude stiffness (h1 = 1, h2 = β2) is stiffer by a known amount.
  const Matrix6 C0 = stiffness_of(*make_material_point(*model, kIso, elastic_at(f, T, std::nullopt)));
  EXPECT_NEAR(C0(5, 5), g1 * (kIso[1] + kIso[2]) + kIso[9] * g2 * kIso[3] * group, 1e-12 * C0(5, 5));
}

// Two implementations: the point's stiffness at the amplitude and the model's moduli of a shear test
// at that amplitude (the fit's evaluate()), for amplitudes across the damage law.
TEST(ElasticAtAmplitude, FritzsonShearStiffnessEqualsTheModelsShearTestModuliAtEveryAmplitude) {
  const auto model = make_model("fritzson-iso", {{"reference_C", 23.0}});
  double last = HUGE_VAL;
  for (double gamma : {1e-4, 0.005, 0.045, 0.1, 0.58}) {
    const Matrix6 C = stiffness_of(*make_material_point(*model, kIso, elastic_at(55.0, 80.0, shear_amplitude(gamma))));
    TestCondition c;
    c.mode = TestMode::shear, c.frequency_Hz = 55.0, c.temperature_C = 80.0, c.strain_amplitude = gamma;
    EXPECT_NEAR(C(5, 5), model->moduli(kIso.data(), c).storage, 1e-12) << "gamma " << gamma;
    EXPECT_LT(C(5, 5), last) << "the secant modulus falls with the amplitude";
    last = C(5, 5);
  }
}

// Plane strain pure shear (e11 = −e22 = ε, the gap bottom) has the deviatoric norm √2 ε, as a simple
// shear of γ = 2ε: the same stiffness.
TEST(ElasticAtAmplitude, FritzsonReadsTheDeviatoricNormOfTheOscillation) {
  const auto model = make_model("fritzson-iso", {{"reference_C", 23.0}});
  Vector6 plane = Vector6::Zero();
  plane[0] = -0.03, plane[1] = 0.03;
  const Matrix6 a = stiffness_of(*make_material_point(*model, kIso, elastic_at(10.0, 40.0, plane)));
  const Matrix6 b = stiffness_of(*make_material_point(*model, kIso, elastic_at(10.0, 40.0, shear_amplitude(0.06))));
  EXPECT_NEAR(a(5, 5), b(5, 5), 1e-13);
}

// A hold caps the drivers as at the complete level: beyond it the stiffness is that at the hold.
TEST(ElasticAtAmplitude, TheDamageHoldCapsTheAmplitudeTheCardIsReadAt) {
  const auto model = make_model("fritzson-iso", {{"reference_C", 23.0}});
  PointOptions held = elastic_at(34.0, 80.0, shear_amplitude(0.6));
  held.damage_driver_hold = {0.045 / std::sqrt(2.0)};
  const Matrix6 beyond = stiffness_of(*make_material_point(*model, kIso, held));
  const Matrix6 at = stiffness_of(*make_material_point(*model, kIso, elastic_at(34.0, 80.0, shear_amplitude(0.045))));
  EXPECT_NEAR(beyond(5, 5), at(5, 5), 1e-13);
  const Matrix6 free = stiffness_of(*make_material_point(*model, kIso, elastic_at(34.0, 80.0, shear_amplitude(0.6))));
  EXPECT_LT(free(5, 5), 0.9 * at(5, 5));
}

// The anisotropic card reads A1 on the fibre strain and A2 on the fibre shears: an in-plane (1–2)
// oscillation leaves the fibre shear stiffness C44 at its A2 small-amplitude value only when its
// drivers are zero — here e33 = −(e11 + e22)/3 ≠ 0 drives A1 and A2, so both soften.
TEST(ElasticAtAmplitude, AnisotropicFritzsonSoftensEveryPartTheOscillationDrives) {
  const std::vector<double> p{4000.0, 2.5, 2.0, 0.21, 0.008, 2.5, 0.25, 0.6, -2.0, 0.5, 0.5, 0.0065, 0.008, 0.6,
                              10.0, 8.0, 0.7, 0.008, 2.5, 0.4, 0.5, -2.2, 0.5, 0.5, 0.006, 0.008,
                              1.2, 1.0, 0.1, 0.008, 2.5, 0.35, 0.6, -2.0, 0.5, 0.5, 0.006, 0.008};
  const auto model = make_model("fritzson", {{"reference_C", 23.0}});
  Vector6 a = Vector6::Zero();
  a[1] = 0.08;  // e22 only: e33 deviatoric −0.027
  const Matrix6 C = stiffness_of(*make_material_point(*model, p, elastic_at(55.0, 80.0, a)));
  const Matrix6 C0 = stiffness_of(*make_material_point(*model, p, elastic_at(55.0, 80.0, std::nullopt)));
  EXPECT_LT(C(5, 5), 0.8 * C0(5, 5));
  EXPECT_LT(C(2, 2) - C(0, 2), C0(2, 2) - C0(0, 2));
  EXPECT_LT(C(3, 3), C0(3, 3));
}

// A model whose moduli do not depend on the amplitude answers alike at every amplitude.
TEST(ElasticAtAmplitude, AnAmplitudeIndependentCardIgnoresTheAmplitude) {
  const auto model = make_model("prony", {{"bulk_modulus", true}, {"terms", 1}});
  const std::vector<double> p{1.0, 2.0, 0.1, 300.0};
  const Matrix6 a = stiffness_of(*make_material_point(*model, p, elastic_at(5.0, NAN, shear_amplitude(0.5))));
  const Matrix6 b = stiffness_of(*make_material_point(*model, p, elastic_at(5.0, NAN, std::nullopt)));
  EXPECT_EQ(a, b);
}

TEST(ElasticAtAmplitude, ANonFiniteAmplitudeIsAUsageError) {
  const auto model = make_model("fritzson-iso", {{"reference_C", 23.0}});
  EXPECT_THROW(make_material_point(*model, kIso, elastic_at(10.0, 40.0, shear_amplitude(NAN))),
               fitlib::core::UsageError);
}

}  // namespace
