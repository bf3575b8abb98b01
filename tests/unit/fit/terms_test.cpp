// Term-count selection: AIC, BIC and pyvisco's residual-ratio rule, and solver caps.
#include <gtest/gtest.h>

#include "fit_testing.hpp"
#include "fitlib/fit/terms.hpp"

using namespace fitlib;
using namespace fitlib::fit::testing;

namespace {

data::DynamicTestTable three_term_data() {
  const auto truth = prony_parameters(1.0, {2.0, 5.0, 3.0}, {1e-3, 0.1, 10.0});
  return synthetic_table(*prony(3), truth, log_frequencies(1e-3, 1e3, 40), 0.005, 21);
}

}  // namespace

TEST(Terms, BicFindsTheTrueTermCount) {
  const auto table = three_term_data();
  fit::TermOptions t;
  t.method = fit::TermMethod::sweep;  // the N-sweep and its rules (the spectrum: spectrum_test)
  t.max_terms = 6;
  const auto sel = fit::select_terms("prony", {{"mode", "shear"}}, table, {}, t);
  ASSERT_EQ(sel.rows.size(), 6u);
  EXPECT_EQ(sel.by_bic, 3);
  EXPECT_EQ(sel.chosen, 3);
  EXPECT_EQ(sel.rule, fit::TermRule::bic);
  EXPECT_EQ(sel.result.values.size(), 7u);
  // The table is consistent with its rules.
  double min_cost = 1e300;
  for (const auto& r : sel.rows) min_cost = std::min(min_cost, r.cost);
  for (const auto& r : sel.rows) {
    if (r.terms < sel.by_ratio) {
      EXPECT_GT(r.cost, 1.5 * min_cost);
    } else if (r.terms == sel.by_ratio) {
      EXPECT_LE(r.cost, 1.5 * min_cost);
    }
    EXPECT_GE(r.bic, sel.rows[sel.by_bic - 1].bic);
    EXPECT_GE(r.aic, sel.rows[sel.by_aic - 1].aic);
    EXPECT_GT(r.wall_time_s, 0.0);
  }
}

TEST(Terms, SolverCapReportsItsAccuracyPenalty) {
  const auto table = three_term_data();
  fit::TermOptions t;
  t.method = fit::TermMethod::sweep;  // the N-sweep and its rules (the spectrum: spectrum_test)
  t.max_terms = 5;
  t.solver_cap = 2;
  const auto sel = fit::select_terms("prony", {{"mode", "shear"}}, table, {}, t);
  EXPECT_EQ(sel.unconstrained, 3);
  EXPECT_EQ(sel.chosen, 2);
  EXPECT_GT(sel.cap_cost_ratio, 1.0);
  EXPECT_GT(sel.cap_storage_rms_ratio, 1.0);
  ASSERT_FALSE(sel.messages.empty());
  EXPECT_NE(sel.messages.back().find("cap"), std::string::npos);
  EXPECT_EQ(sel.result.values.size(), 5u);
}

TEST(Terms, RatioRuleAndTheTable) {
  const auto table = three_term_data();
  fit::TermOptions t;
  t.method = fit::TermMethod::sweep;  // the N-sweep and its rules (the spectrum: spectrum_test)
  t.max_terms = 4;
  t.rule = fit::TermRule::residual_ratio;
  const auto sel = fit::select_terms("prony", {{"mode", "shear"}}, table, {}, t);
  EXPECT_EQ(sel.chosen, sel.by_ratio);
  const std::string text = fit::format_term_table(sel);
  EXPECT_NE(text.find("BIC"), std::string::npos);
  EXPECT_NE(text.find("<- chosen"), std::string::npos);
  EXPECT_EQ(fit::parse_term_rule("ratio"), fit::TermRule::residual_ratio);
  EXPECT_EQ(fit::choose_terms(sel.rows, fit::TermRule::bic, 1.5, 1), 1);
}
