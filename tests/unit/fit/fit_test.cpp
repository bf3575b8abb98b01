// Backends on synthetic data with known parameters: recovery, the auto rule, determinism,
// interval coverage, positivity, rank deficiency.
#include <gtest/gtest.h>

#include "fit_testing.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/shift_laws.hpp"
#include "fitlib/fit/terms.hpp"

#include <algorithm>

using namespace fitlib;
using namespace fitlib::fit::testing;

namespace {

const std::vector<double> kTrue3 = prony_parameters(1.0, {2.0, 5.0, 3.0}, {1e-3, 0.1, 10.0});

bool mentions(const fit::FitResult& r, const std::string& text) {
  for (const auto& m : r.messages)
    if (m.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST(Fit, NnlsOnTheTrueTimeGridRecoversTheModuliExactly) {
  const auto model = prony(3);
  const auto table = synthetic_table(*model, kTrue3, log_frequencies(1e-3, 1e3, 40), 0.0, 1);
  std::vector<double> start = kTrue3;
  for (int i = 0; i <= 3; ++i) start[i] = 1.0;  // moduli unknown, τ on the true grid
  fit::FitOptions o;
  o.fixed = {"tau_1", "tau_2", "tau_3"};
  const auto r = fit::fit(model, table, o, &start);
  EXPECT_EQ(r.backend_used, "nnls");  // auto: no free non-linear parameter
  for (int i = 0; i <= 3; ++i) EXPECT_NEAR(r.values[i], kTrue3[i], 1e-8 * kTrue3[i]);
  EXPECT_LT(r.metrics.rms_log10_storage, 1e-10);
  EXPECT_TRUE(r.metrics.converged);
}

TEST(Fit, NnlsBackendHoldsNonLinearParametersAndSaysSo) {
  const auto model = prony(3);
  const auto table = synthetic_table(*model, kTrue3, log_frequencies(1e-3, 1e3, 40), 0.01, 2);
  fit::FitOptions o;
  o.backend = fit::Backend::nnls;
  const auto r = fit::fit(model, table, o);
  EXPECT_EQ(r.backend_used, "nnls");
  const auto start = model->initial_parameters(fit::summarize(table));
  for (int i = 4; i < 7; ++i) {
    EXPECT_EQ(r.values[i], start[i]);
    EXPECT_TRUE(r.parameters[i].fixed);
    EXPECT_FALSE(r.parameters[i].std_error);
  }
  EXPECT_TRUE(mentions(r, "held"));
}

TEST(Fit, CeresRecoversFreeTimeConstants) {
  const auto model = prony(3);
  const auto table = synthetic_table(*model, kTrue3, log_frequencies(1e-4, 1e4, 50), 0.0, 3);
  const auto r = fit::fit(model, table, {});
  EXPECT_EQ(r.backend_used, "nnls+ceres");
  ASSERT_TRUE(r.metrics.converged);
  for (std::size_t i = 0; i < kTrue3.size(); ++i)
    EXPECT_NEAR(r.values[i], kTrue3[i], 1e-5 * kTrue3[i]) << r.parameters[i].name;
  EXPECT_EQ(r.metrics.rank, 7);
}

TEST(Fit, NloptMultistartThenCeresReachesTheSameOptimum) {
  const auto model = prony(2);
  const auto truth = prony_parameters(0.5, {4.0, 2.0}, {0.01, 10.0});
  const auto table = synthetic_table(*model, truth, log_frequencies(1e-3, 1e3, 30), 0.0, 4);
  fit::FitOptions o;
  o.backend = fit::Backend::nlopt;
  o.multistart = 6;
  const auto r = fit::fit(model, table, o);
  EXPECT_EQ(r.backend_used, "nlopt+ceres");
  for (std::size_t i = 0; i < truth.size(); ++i) EXPECT_NEAR(r.values[i], truth[i], 1e-5 * truth[i]);
}

TEST(Fit, SameInputAndSeedGiveBitIdenticalResults) {
  const auto model = prony(3);
  const auto table = synthetic_table(*model, kTrue3, log_frequencies(1e-3, 1e3, 40), 0.02, 5);
  for (auto backend : {fit::Backend::automatic, fit::Backend::nlopt, fit::Backend::staged}) {
    fit::FitOptions o;
    o.backend = backend;
    o.multistart = 4;
    o.seed = 42;
    const auto a = fit::fit(model, table, o);
    const auto b = fit::fit(model, table, o);
    ASSERT_EQ(a.values.size(), b.values.size());
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      EXPECT_EQ(a.values[i], b.values[i]) << fit::to_string(backend) << " " << a.parameters[i].name;
      EXPECT_EQ(a.parameters[i].std_error, b.parameters[i].std_error);
    }
    EXPECT_EQ(a.metrics.cost, b.metrics.cost);
  }
}

// 1 % noise: the 95 % intervals contain the true value in about 95 % of (trial, parameter)
// pairs. 200 trials × 5 parameters.
TEST(Fit, NinetyFivePercentIntervalsCoverTheTruth) {
  const auto model = prony(2);
  const auto truth = prony_parameters(1.0, {2.0, 3.0}, {0.01, 1.0});
  const auto freqs = log_frequencies(1e-2, 1e3, 30);
  int inside = 0, total = 0, missing = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto table = synthetic_table(*model, truth, freqs, 0.01, 1000 + trial);
    const auto r = fit::fit(model, table, {});
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const auto& pr = r.parameters[i];
      if (!pr.ci95_low || !pr.ci95_high) {
        ++missing;
        continue;
      }
      EXPECT_GT(*pr.ci95_low, 0.0);
      inside += *pr.ci95_low <= truth[i] && truth[i] <= *pr.ci95_high;
      ++total;
    }
  }
  EXPECT_EQ(missing, 0);
  const double coverage = double(inside) / total;
  RecordProperty("coverage", std::to_string(coverage));
  EXPECT_GE(coverage, 0.90);
  EXPECT_LE(coverage, 0.99);
}

TEST(Fit, NoNegativeModuliOrTimesOverNoisyFits) {
  const auto model = prony(4);
  const auto truth = prony_parameters(0.3, {1.0, 0.2, 3.0, 0.05}, {1e-4, 1e-2, 1.0, 100.0});
  const auto freqs = log_frequencies(1e-3, 1e4, 40);
  int negative = 0, non_finite = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const auto table = synthetic_table(*model, truth, freqs, 0.05, 5000 + trial);
    const auto r = fit::fit(model, table, {});
    for (double v : r.values) {
      negative += v < 0.0;
      non_finite += !std::isfinite(v);
    }
    for (const auto& pr : r.parameters) {
      if (pr.ci95_low) negative += *pr.ci95_low < 0.0;
      if (pr.std_error) non_finite += !std::isfinite(*pr.std_error);
    }
  }
  EXPECT_EQ(negative, 0);
  EXPECT_EQ(non_finite, 0);
}

// Two terms with the same start τ and a data set that only needs one: the Jacobian is rank
// deficient; the report names the parameters, and the flagged term is merged into the other
// and the fit re-polished (issue 10: never kept silently). What is left is the one true term.
TEST(Fit, RankDeficiencyIsReportedAndTheTermMerged) {
  const auto model = prony(2);
  const auto one_term = prony(1);
  const auto table = synthetic_table(*one_term, prony_parameters(1.0, {2.0}, {0.1}),
                                     log_frequencies(1e-2, 1e2, 20), 0.0, 6);
  std::vector<double> start = prony_parameters(1.0, {1.0, 1.0}, {0.1, 0.1});
  fit::FitOptions o;
  o.backend = fit::Backend::ceres;
  const auto r = fit::fit(model, table, o, &start);
  EXPECT_TRUE(mentions(r, "not identifiable"));
  EXPECT_TRUE(mentions(r, "merged"));
  // One modulus removed (0, its time without interval), the other carries the true term.
  const double g1 = r.values[1], g2 = r.values[2];
  EXPECT_EQ(std::min(g1, g2), 0.0);
  EXPECT_NEAR(std::max(g1, g2), 2.0, 1e-6);
  EXPECT_NEAR(r.values[0], 1.0, 1e-6);
  int without = 0;
  for (const auto& pr : r.parameters)
    if (!pr.std_error) {
      ++without;
      EXPECT_FALSE(pr.reason.empty()) << pr.name;
    }
  EXPECT_GE(without, 2);
  EXPECT_EQ(r.metrics.rank, r.metrics.n_free);
}

TEST(Fit, RelativeResidualsAndWeightsRun) {
  const auto model = prony(3);
  const auto table = synthetic_table(*model, kTrue3, log_frequencies(1e-3, 1e3, 40), 0.0, 7);
  fit::FitOptions o;
  o.residual = fit::ResidualKind::relative;
  o.storage_weight = 10.0;
  const auto r = fit::fit(model, table, o);
  EXPECT_LT(r.metrics.max_rel_error, 1e-6);
  EXPECT_NE(r.objective.find("relative"), std::string::npos);
}

TEST(Fit, UnknownFixedNameIsAUsageError) {
  const auto model = prony(1);
  const auto table = synthetic_table(*model, prony_parameters(1, {1}, {1}), log_frequencies(0.1, 10, 5), 0, 1);
  fit::FitOptions o;
  o.fixed = {"tau_9"};
  EXPECT_THROW(fit::fit(model, table, o), core::UsageError);
}

// Prony terms are exchangeable; the fit returns them sorted by τ (the bundled 6-term table
// otherwise comes back with its fastest term last).
TEST(Fit, SeriesTermsComeSortedByTimeConstant) {
  const auto table = data::read_dynamic_table(std::string(FITLIB_SOURCE_DIR) +
                                              "/datasets/materials/synthetic-prony-shear.csv");
  const auto truth = prony_parameters(2.0, {3.0, 2.5, 2.0, 1.5, 1.0, 0.8},
                                      {1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0});
  const auto r = fit::fit(prony(6), table, {});
  for (int k = 8; k < 13; ++k) EXPECT_LT(r.values[k - 1], r.values[k]);
  for (std::size_t i = 0; i < truth.size(); ++i)
    EXPECT_NEAR(r.values[i], truth[i], 0.25 * truth[i]) << r.parameters[i].name;
}

// A temperature law fitted to isotherm shifts it cannot follow says so in the verdict (docs/
// fitting.md, "Quality verdict"); shifts the law reproduces exactly give no such warning.
TEST(ShiftLawVerdict, LawThatMissesTheShiftsWarns) {
  const auto model = fitlib::fit::testing::prony(1);
  const auto p = fitlib::fit::testing::prony_parameters(1.0, {2.0}, {0.1});
  const auto table = fitlib::fit::testing::synthetic_table(*model, p, fitlib::fit::testing::log_frequencies(0.01, 100, 9), 0.0, 1);
  const fitlib::fit::FitResult result = fitlib::fit::fit(fitlib::fit::testing::prony(1), table, {});
  const std::vector<double> T{-20, 0, 20, 40, 60, 80};
  std::vector<double> wlf, kinked;
  for (double t : T) {
    wlf.push_back(-8.86 * (t - 20) / (101.6 + t - 20));   // WLF itself, T_ref 20 degC
    kinked.push_back(t < 40 ? -0.15 * (t - 20) : -3.0 - 0.02 * (t - 40) + 1.5 * (t >= 60));  // a step
  }
  const auto law_warning = [](const fitlib::fit::FitResult& r) {
    return std::any_of(r.quality.warnings.begin(), r.quality.warnings.end(), [](const std::string& w) {
      return w.find("misses the isotherm shifts") != std::string::npos;
    });
  };
  const auto exact = fitlib::fit::with_law_from_shifts(result, T, wlf, 20.0, fitlib::model::ShiftLaw::wlf, 3);
  EXPECT_FALSE(law_warning(exact));
  const auto missed = fitlib::fit::with_law_from_shifts(result, T, kinked, 20.0, fitlib::model::ShiftLaw::wlf, 3);
  EXPECT_TRUE(law_warning(missed));
  EXPECT_FALSE(missed.quality.acceptable());
}

// A card with as many free parameters as residuals reproduces the points whatever it is: the verdict
// warns (not acceptable) although its errors are round-off; one more frequency than parameters needs
// clears it (docs/decisions.md "Quality: no residual degrees of freedom").
TEST(QualityVerdict, NoResidualDegreesOfFreedomIsAWarning) {
  const auto model = fitlib::fit::testing::prony(1);  // G_inf, G_1, tau_1
  const auto p = fitlib::fit::testing::prony_parameters(1.0, {2.0}, {0.1});
  const auto warned = [](const fitlib::fit::FitResult& r) {
    return std::any_of(r.quality.warnings.begin(), r.quality.warnings.end(), [](const std::string& w) {
      return w.find("the data do not determine the card") != std::string::npos;
    });
  };
  const auto one = fitlib::fit::testing::synthetic_table(*model, p, {1.0}, 0.0, 1);  // 2 residuals, 3 free
  const fitlib::fit::FitResult under = fitlib::fit::fit(fitlib::fit::testing::prony(1), one, {});
  EXPECT_TRUE(warned(under));
  EXPECT_FALSE(under.quality.acceptable());
  const auto two = fitlib::fit::testing::synthetic_table(*model, p, {0.3, 3.0}, 0.0, 1);  // 4 residuals
  const fitlib::fit::FitResult enough = fitlib::fit::fit(fitlib::fit::testing::prony(1), two, {});
  EXPECT_FALSE(warned(enough));
}

// A fractional Zener fitted to a power law seen over three decades (no plateau in the window):
// its central time and modulus stay inside the admissible window (docs/fitting.md "Admissible
// terms") instead of running to τ = 1e-10 s with E_delta 40× the largest measured storage.
TEST(AdmissibleWindow, FractionalZenerStaysInsideTheWindowOnAPowerLaw) {
  fitlib::data::DynamicTestTable table;
  for (double f : fitlib::fit::testing::log_frequencies(0.1, 100, 7)) {
    fitlib::data::DynamicTestRow row;
    row.condition.mode = fitlib::model::TestMode::uniaxial;
    row.condition.frequency_Hz = f;
    row.storage_MPa = 3.0 + 2.0 * std::pow(f, 0.3);
    row.loss_MPa = 0.2 * row.storage_MPa * std::pow(f, 0.05);
    table.rows.push_back(row);
  }
  const auto r = fitlib::fit::fit(fitlib::model::make_model("fractional-zener", {{"mode", "uniaxial"}}), table, {});
  ASSERT_TRUE(r.admissible.applies);
  const double e_delta = r.values[1], tau = r.values[2];
  EXPECT_GE(tau, r.admissible.tau_min_s * (1 - 1e-12));
  EXPECT_LE(tau, r.admissible.tau_max_s * (1 + 1e-12));
  EXPECT_LE(e_delta, r.admissible.modulus_max_MPa * (1 + 1e-12));
  EXPECT_LT(r.metrics.max_rel_error, 0.15);
}

// A fractional Zener whose central time lies two decades below the data's fastest (τ 1e-6 s, data
// 0.1–100 Hz: the admitted window starts at 1.6e-4 s) ends with τ on its bound, and the verdict says
// the card holds the bound, not a measured value; the same law with τ 0.05 s is fitted inside the
// window without that warning. (A hand-typed 0.1–100 Hz table gave τ at its bound silently.)
TEST(AdmissibleWindow, AParameterEndingOnItsBoundIsAWarning) {
  using namespace fitlib::fit::testing;
  const auto model = fitlib::model::make_model("fractional-zener", {{"mode", "shear"}});
  const auto on_bound = [](const fitlib::fit::FitResult& r) {
    return std::any_of(r.quality.warnings.begin(), r.quality.warnings.end(),
                       [](const std::string& w) { return w.rfind("tau = ", 0) == 0 && w.find("ended on its bound") != std::string::npos; });
  };
  const auto frequencies = log_frequencies(0.1, 100, 7);
  const auto fast = fitlib::fit::fit(model, synthetic_table(*model, {1.5, 10.0, 1e-6, 0.3}, frequencies, 0.0, 1), {});
  ASSERT_TRUE(fast.admissible.applies);
  EXPECT_NEAR(fast.values[2], fast.admissible.tau_min_s, 1e-9 * fast.admissible.tau_min_s);
  EXPECT_TRUE(on_bound(fast));
  const auto inside = fitlib::fit::fit(model, synthetic_table(*model, {1.5, 10.0, 0.05, 0.3}, frequencies, 0.0, 1), {});
  EXPECT_NEAR(inside.values[2], 0.05, 1e-4);
  EXPECT_FALSE(on_bound(inside));
}

// Every backend, residual kind, term rule and term method has a name that reads back.
TEST(EnumNames, FitEnumsReadBack) {
  using namespace fitlib::fit;
  for (Backend b : {Backend::automatic, Backend::nnls, Backend::ceres, Backend::nlopt, Backend::staged})
    EXPECT_EQ(parse_backend(to_string(b)), b);
  for (ResidualKind k : {ResidualKind::log10, ResidualKind::relative, ResidualKind::complex})
    EXPECT_EQ(parse_residual_kind(to_string(k)), k);
  for (TermRule r : {TermRule::bic, TermRule::aic, TermRule::residual_ratio}) EXPECT_EQ(parse_term_rule(to_string(r)), r);
  EXPECT_EQ(parse_backend("automatic"), Backend::automatic);
  EXPECT_EQ(parse_term_rule("pyvisco"), TermRule::residual_ratio);
  EXPECT_EQ(parse_term_method("sweep"), TermMethod::sweep);
  EXPECT_THROW(parse_backend("gauss"), fitlib::core::UsageError);
}

// Rows where the true linear temperature factor has reached its floor (g = 1 − 0.01 (T − 20) ≤ 10⁻³
// from 119.9 °C): the floor has no gradient, the fit ends with a law that has no material at some
// data temperatures, and its verdict says that eval and scenes will refuse the card there (besides
// the misses). Rows inside the law: c_T recovered, no such warning.
TEST(TemperatureLawVerdict, FittedLawWithoutMaterialAtADataTemperatureWarns) {
  using namespace fitlib::fit::testing;
  const auto model = fitlib::model::make_model("prony", {{"terms", 1}, {"reference_C", 20.0}, {"linear_factor", true}});
  const std::vector<double> truth = {1.0, 2.0, 0.1, 0.01};  // E∞, E1, τ1 (s), c_T (1/°C)
  const auto law_warning = [](const fitlib::fit::FitResult& r) {
    return std::any_of(r.quality.warnings.begin(), r.quality.warnings.end(), [](const std::string& w) {
      return w.find("temperature law describes no material at the data's") != std::string::npos;
    });
  };
  fitlib::data::DynamicTestTable table;
  for (double T : {20.0, 60.0, 100.0, 130.0}) {
    const auto isotherm = synthetic_table(*model, truth, log_frequencies(0.1, 100, 5), 0.0, 1,
                                          fitlib::model::TestMode::shear, T);
    table.rows.insert(table.rows.end(), isotherm.rows.begin(), isotherm.rows.end());
  }
  const auto beyond = fitlib::fit::fit(model, table, {});
  EXPECT_TRUE(law_warning(beyond)) << testing::PrintToString(beyond.quality.warnings);
  EXPECT_FALSE(beyond.quality.acceptable());
  table.rows.resize(15);  // 20, 60 and 100 °C only
  const auto inside = fitlib::fit::fit(model, table, {});
  EXPECT_FALSE(law_warning(inside)) << testing::PrintToString(inside.quality.warnings);
  EXPECT_NEAR(inside.values[3], 0.01, 1e-6);
}
