// The smooth spectrum (`--terms auto`) with a temperature law: the law's constants start from the
// model-free isotherm shifts and are refined with the spectrum (docs/fitting.md "Default: a
// smooth spectrum"). Synthetic isotherms of known truth: a 13-term Prony series under a WLF,
// Arrhenius or polynomial law.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "fit_testing.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "fitlib/fit/nnls.hpp"
#include "fitlib/fit/terms.hpp"
#include "../../../fitlib/src/fit/spectrum_system.hpp"

using namespace fitlib;

namespace {

constexpr double kRefC = 20.0;

nlohmann::json law_options(const std::string& law) {
  nlohmann::json o = {{"mode", "uniaxial"}, {"temperature_law", law}, {"reference_C", kRefC}};
  if (law == "polynomial") o["polynomial_degree"] = 2;
  return o;
}

// 13 terms, one per decade 1e-8 … 1e4 s, E∞ = 5 MPa, then the law's constants.
std::vector<double> truth(const std::vector<double>& law_constants) {
  std::vector<double> p{5.0};
  for (int i = 0; i < 13; ++i) p.push_back(60.0 * std::pow(10.0, -0.05 * i));
  for (int i = 0; i < 13; ++i) p.push_back(std::pow(10.0, -8.0 + i));
  p.insert(p.end(), law_constants.begin(), law_constants.end());
  return p;
}

// Isotherms −10 … 60 °C, 10 frequencies 0.1 … 100 Hz each, moduli × (1 + noise·N(0,1)).
data::DynamicTestTable isotherms(const std::string& law, const std::vector<double>& constants, double noise) {
  nlohmann::json o = law_options(law);
  o["terms"] = 13;
  const auto m = model::make_model("prony", o);
  const auto p = truth(constants);
  core::Rng rng(5);
  data::DynamicTestTable table;
  for (double t : {-10.0, 0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0})
    for (int i = 0; i < 10; ++i) {
      data::DynamicTestRow row;
      row.condition.mode = model::TestMode::uniaxial;
      row.condition.frequency_Hz = 0.1 * std::pow(10.0, i / 3.0);
      row.condition.temperature_C = t;
      const auto mod = m->moduli(p.data(), row.condition);
      row.storage_MPa = mod.storage * (1.0 + noise * rng.normal());
      row.loss_MPa = mod.loss * (1.0 + noise * rng.normal());
      row.set = "T" + std::to_string(static_cast<int>(t));
      table.rows.push_back(row);
    }
  return table;
}

fit::TermSelection spectrum_fit(const std::string& law, const data::DynamicTestTable& table) {
  fit::FitOptions o;
  o.residual = fit::kSpectrumResidual;
  o.storage_weight = fit::kSpectrumStorageWeight;
  return fit::select_terms("prony", law_options(law), table, o, fit::TermOptions{});
}

// The law's constants of a result (the model names their slots).
std::vector<double> law_constants(const fit::FitResult& r) {
  std::vector<double> c;
  for (int i : r.model->temperature_law_info().shift_parameters) c.push_back(r.values[i]);
  return c;
}

void expect_spectrum_with_refined_law(const fit::TermSelection& sel) {
  EXPECT_EQ(sel.method, fit::TermMethod::spectrum);
  EXPECT_EQ(sel.result.backend_used.rfind("spectrum+", 0), 0u) << sel.result.backend_used;
  bool refined = false;
  for (const auto& m : sel.result.messages) refined = refined || m.find("law constants refined") != std::string::npos;
  EXPECT_TRUE(refined);
  EXPECT_TRUE(sel.result.admissible.applies);
}

}  // namespace

TEST(Spectrum, WlfConstantsAreRecoveredWithTheSpectrum) {
  const auto table = isotherms("wlf", {8.86, 101.6}, 0.005);
  const auto sel = spectrum_fit("wlf", table);
  expect_spectrum_with_refined_law(sel);
  const auto c = law_constants(sel.result);
  ASSERT_EQ(c.size(), 2u);
  std::printf("WLF: C1 %.4f (8.86), C2 %.3f K (101.6), rms log10 E' %.5f E'' %.5f, %d terms\n", c[0], c[1],
              sel.result.metrics.rms_log10_storage, sel.result.metrics.rms_log10_loss, sel.chosen);
  // The model-free shifts alone give C1 8.985, C2 102.67 (1.4 %, 1.1 % off): the refinement
  // with the spectrum brings both within 0.5 %.
  EXPECT_NEAR(c[0], 8.86, 0.005 * 8.86);
  EXPECT_NEAR(c[1], 101.6, 0.005 * 101.6);
  EXPECT_LT(sel.result.metrics.rms_log10_storage, 0.005);  // the noise level (0.5 % ≈ 0.002 decade)
  EXPECT_LT(sel.result.metrics.rms_log10_loss, 0.03);
}

TEST(Spectrum, ArrheniusEnergyIsRecoveredWithTheSpectrum) {
  const auto table = isotherms("arrhenius", {150.0}, 0.005);
  const auto sel = spectrum_fit("arrhenius", table);
  expect_spectrum_with_refined_law(sel);
  const auto c = law_constants(sel.result);
  ASSERT_EQ(c.size(), 1u);
  std::printf("Arrhenius: E_a %.3f kJ/mol (150), rms log10 E' %.5f E'' %.5f\n", c[0],
              sel.result.metrics.rms_log10_storage, sel.result.metrics.rms_log10_loss);
  EXPECT_NEAR(c[0], 150.0, 0.005 * 150.0);
  EXPECT_LT(sel.result.metrics.rms_log10_storage, 0.005);
}

TEST(Spectrum, PolynomialLawIsRecoveredWithTheSpectrum) {
  // log10 a_T = −0.12 ΔT + 4e-4 ΔT² (a convex curve like WLF's over 70 K).
  const auto table = isotherms("polynomial", {-0.12, 4e-4}, 0.005);
  const auto sel = spectrum_fit("polynomial", table);
  expect_spectrum_with_refined_law(sel);
  const auto c = law_constants(sel.result);
  ASSERT_EQ(c.size(), 2u);
  std::printf("polynomial: C1 %.5f (-0.12), C2 %.3e (4e-4), rms log10 E' %.5f\n", c[0], c[1],
              sel.result.metrics.rms_log10_storage);
  // Compare the shifts the law gives over the data's temperatures (the constants trade off).
  for (double dt : {-30.0, 40.0})
    EXPECT_NEAR(c[0] * dt + c[1] * dt * dt, -0.12 * dt + 4e-4 * dt * dt, 0.05) << dt;
  EXPECT_LT(sel.result.metrics.rms_log10_storage, 0.005);
}

TEST(Spectrum, OneIsothermHoldsTheLawAndSaysSo) {
  auto table = isotherms("wlf", {8.86, 101.6}, 0.0);
  std::vector<data::DynamicTestRow> rows;
  for (const auto& r : table.rows)
    if (r.set == "T20") rows.push_back(r);
  table.rows = rows;
  const auto sel = spectrum_fit("wlf", table);
  EXPECT_EQ(sel.result.backend_used.rfind("spectrum+", 0), 0u);
  bool said = false;
  for (const auto& m : sel.result.messages) said = said || m.find("one isotherm") != std::string::npos;
  EXPECT_TRUE(said);
  EXPECT_LT(sel.result.metrics.rms_log10_storage, 0.005);  // noise-free; the smoothing's bias
}

// A hand-typed table whose storage falls with frequency shows no relaxation a series can hold: the
// smooth spectrum keeps no positive term. The card's one term is a removed one (modulus 0, said
// so), not a modulus of 1 MPa that nothing fitted (the log transform moved the 0 start to 1 and
// the report said "1 positive terms kept").
TEST(Spectrum, NoPositiveTermLeavesARemovedTermAtZeroAndSaysSo) {
  data::DynamicTestTable table;
  const double rows[4][3] = {{1, 2.3, 0.38}, {10, 3.0, 0.5}, {100, 3.5, 0.3}, {1000, 1.0, 2.0}};
  for (const auto& r : rows) {
    data::DynamicTestRow row;
    row.condition.mode = model::TestMode::shear;
    row.condition.frequency_Hz = r[0];
    row.storage_MPa = r[1], row.loss_MPa = r[2];
    table.rows.push_back(row);
  }
  fit::FitOptions o;
  o.residual = fit::kSpectrumResidual;
  o.storage_weight = fit::kSpectrumStorageWeight;
  const auto sel = fit::select_terms("prony", {{"mode", "shear"}}, table, o, fit::TermOptions{});
  ASSERT_EQ(sel.method, fit::TermMethod::spectrum);
  const auto& r = sel.result;
  ASSERT_EQ(r.values.size(), 3u);  // G_inf, G_1, tau_1
  EXPECT_EQ(r.values[1], 0.0);
  EXPECT_NE(r.parameters[1].reason.find("removed term"), std::string::npos) << r.parameters[1].reason;
  EXPECT_GT(r.values[0], 1.0);
  bool said = false;
  for (const auto& m : r.messages) said = said || m.find("0 positive terms kept") != std::string::npos;
  EXPECT_TRUE(said);
  // Elastic data (loss 0): round-off moduli of 1e-16 MPa are no terms either.
  for (auto& row : table.rows) row.storage_MPa = 2.3, row.loss_MPa = 0.0;
  const auto elastic = fit::select_terms("prony", {{"mode", "shear"}}, table, o, fit::TermOptions{}).result;
  ASSERT_EQ(elastic.values.size(), 3u);
  EXPECT_EQ(elastic.values[1], 0.0);
  EXPECT_NEAR(elastic.values[0], 2.3, 1e-12);
  EXPECT_EQ(elastic.quality.figures.front().max_at_frequency_Hz, 1.0);  // not "at 0 Hz"
}

// The λ path's warm-started active set on the normal equations against the independent
// QR-checked nnls() on the stacked system [R; √λ D] y ≈ [c; 0], at every λ of the default path,
// on pyvisco's master (53 time constants over 26 decades: an ill-conditioned design).
TEST(Spectrum, WarmStartedPathMatchesTheStackedNnlsAtEveryLambda) {
  const auto table = fit::testing::read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  fit::FitOptions o;
  o.residual = fit::kSpectrumResidual;
  o.storage_weight = fit::kSpectrumStorageWeight;
  const auto dense = model::make_model("prony", {{"mode", "uniaxial"}, {"terms", 53}});
  const auto s = fit::detail::make_spectrum_system(dense, table, o, 1e-14, 1e12, {});
  const fit::SpectrumOptions so;
  std::vector<bool> passive;
  for (int k = 0; k < so.lambda_steps; ++k) {
    const double lambda = so.lambda_max * std::pow(so.lambda_min / so.lambda_max, double(k) / (so.lambda_steps - 1));
    const Eigen::VectorXd warm = fit::detail::solve_penalised(s.red, s.d, s.normal, lambda, &passive);
    const int nc = static_cast<int>(s.red.r.cols());
    Eigen::MatrixXd big(nc + s.d.rows(), nc);
    big << s.red.r, std::sqrt(lambda) * s.d;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nc + s.d.rows());
    rhs.head(nc) = s.red.c;
    const Eigen::VectorXd reference = fit::nnls(big, rhs).x;
    EXPECT_GE(warm.minCoeff(), 0.0) << lambda;
    const double ours = s.penalised(warm, lambda), theirs = s.penalised(reference, lambda);
    EXPECT_NEAR(ours, theirs, 1e-8 * theirs) << "lambda " << lambda;
  }
}
