// Life as a distribution (docs/fatigue.md §9): the scatter and covariance life-fit writes into the
// card, and the B10/B50 lives with their 90 % interval.
#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/finite_output.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/fatigue/life_distribution.hpp"
#include "fitlib/fatigue/life_fit.hpp"

namespace fitlib::fatigue {
namespace {

// One mode's life at the design point with peaks `peaks`: N from (6.31) by sum_terms.
ModeLife mode_life(const LifeLaw& law, const std::vector<double>& peaks, double dT) {
  ModeLife m;
  m.mode = Mode::separation;
  for (double p : peaks) m.peaks.push_back({0.0, p, ""});
  m.sum_terms = sum_terms(peaks, law);
  m.life_cycles = std::pow(2.0, -law.b_per_C * dT) / m.sum_terms;
  return m;
}

LifeLaw law_with_scatter(double sigma, double cov_scale) {
  LifeLaw law{4.21028, 11.69, 0.1466, std::nullopt, LifeScatter{"lognormal", sigma, 8}, std::nullopt};
  LawCovariance c{};
  c[0][0] = 4e-4 * cov_scale, c[1][1] = 0.25 * cov_scale, c[2][2] = 1e-4 * cov_scale;
  c[0][1] = c[1][0] = 5e-3 * cov_scale;
  law.covariance = c;
  return law;
}

TEST(LifeDistribution, B10IsBelowB50AndB50IsTheDeterministicLife) {
  const LifeLaw law = law_with_scatter(0.3, 1.0);
  const ModeLife m = mode_life(law, {1.5, 0.9, 1.1}, 10.0);
  const auto d = mode_distribution(m, law, 90.0, 80.0, 3600.0);
  ASSERT_TRUE(d);
  EXPECT_DOUBLE_EQ(d->b50.cycles, m.life_cycles);
  // log10 B10 = log10 N − 1.28155 s (the standard normal's 10 % quantile)
  EXPECT_NEAR(std::log10(d->b10.cycles), std::log10(m.life_cycles) - 1.2815516 * 0.3, 1e-6);
  EXPECT_LT(d->b10.cycles, d->b50.cycles);
  EXPECT_LT(d->b10.low_cycles, d->b10.cycles);
  EXPECT_GT(d->b10.high_cycles, d->b10.cycles);
  EXPECT_DOUBLE_EQ(d->b50.h, d->b50.cycles / 3600.0);
}

TEST(LifeDistribution, IntervalWidensWhenTheConstantsCovarianceGrows) {
  const ModeLife m = mode_life(law_with_scatter(0.3, 1.0), {1.5, 0.9, 1.1}, 10.0);
  const auto narrow = mode_distribution(m, law_with_scatter(0.3, 1.0), 90.0, 80.0, 3600.0);
  const auto wide = mode_distribution(m, law_with_scatter(0.3, 4.0), 90.0, 80.0, 3600.0);
  ASSERT_TRUE(narrow && wide);
  EXPECT_NEAR(wide->constants_sd_log10, 2.0 * narrow->constants_sd_log10, 1e-12);  // sd ∝ √covariance
  EXPECT_GT(std::log10(wide->b10.high_cycles / wide->b10.low_cycles),
            1.99 * std::log10(narrow->b10.high_cycles / narrow->b10.low_cycles));
  LifeLaw none = law_with_scatter(0.3, 1.0);
  none.covariance.reset();
  EXPECT_FALSE(mode_distribution(m, none, 90.0, 80.0, 3600.0)->b10.has_interval);
  none.scatter.reset();
  EXPECT_FALSE(mode_distribution(m, none, 90.0, 80.0, 3600.0));  // no scatter: the median only
}

// The gradient against central differences of log10 N from sum_terms (an independent path).
TEST(LifeDistribution, GradientMatchesFiniteDifferencesOfTheLaw) {
  const std::vector<double> peaks{1.5, 0.9, 1.1, 0.4};
  const LifeLaw law{4.21028, 11.69, 0.1466, std::nullopt};
  const double dT = 12.0;
  auto log10N = [&](double ln_s0, double n, double b) {
    const LifeLaw l{std::exp(ln_s0), n, b, std::nullopt};
    return std::log10(std::pow(2.0, -b * dT) / sum_terms(peaks, l));
  };
  const auto g = log10_life_gradient(peaks, law, dT);
  const double h = 1e-6, x = std::log(law.sigma0_MPa);
  EXPECT_NEAR(g[0], (log10N(x + h, law.n, law.b_per_C) - log10N(x - h, law.n, law.b_per_C)) / (2 * h), 1e-6);
  EXPECT_NEAR(g[1], (log10N(x, law.n + h, law.b_per_C) - log10N(x, law.n - h, law.b_per_C)) / (2 * h), 1e-6);
  EXPECT_NEAR(g[2], (log10N(x, law.n, law.b_per_C + h) - log10N(x, law.n, law.b_per_C - h)) / (2 * h), 1e-6);
}

// life-fit's scatter estimates the noise of synthetic lives of known truth, and its covariance's
// diagonal is the square of the intervals' standard errors.
TEST(LifeDistribution, LifeFitWritesTheScatterAndCovarianceItEstimated) {
  const LifeLaw truth{4.21028, 11.69, 0.1466, std::nullopt};
  core::Rng rng(17);
  std::vector<ObservedLife> cases;
  for (int k = 0; k < 60; ++k) {
    ObservedLife c;
    c.name = "c" + std::to_string(k), c.mode = Mode::separation, c.temperature_C = rng.uniform(60.0, 120.0);
    c.point_peaks_MPa = {{truth.sigma0_MPa * rng.uniform(0.05, 0.4)}};
    c.observed_cycles = 1.0;
    c.observed_cycles = std::pow(10.0, predicted_log10_life(c, truth, 80.0) + 0.2 * rng.normal());
    cases.push_back(c);
  }
  LifeFitOptions o;
  o.start = LifeLaw{8.0, 6.0, 0.05, std::nullopt};
  const LifeFitResult r = fit_life_law(cases, Mode::separation, o);
  ASSERT_TRUE(r.law.scatter && r.law.covariance);
  EXPECT_EQ(r.law.scatter->dof, 57);
  EXPECT_NEAR(r.law.scatter->sigma_log10, 0.2, 0.04);  // 60 draws: the estimate's sd is about 0.02
  EXPECT_NEAR(std::sqrt((*r.law.covariance)[1][1]), r.constants[1].std_error, 1e-12);
  EXPECT_NEAR(std::sqrt((*r.law.covariance)[2][2]), r.constants[2].std_error, 1e-12);
}

TEST(LifeDistribution, CardKeepsScatterAndCovarianceAndTheBundledCardStillReads) {
  FatigueCard c = default_card();
  c.separation = law_with_scatter(0.3, 1.0);
  const FatigueCard back = card_from_json(card_to_json(c), "mem");
  ASSERT_TRUE(back.separation.scatter && back.separation.covariance);
  EXPECT_EQ(back.separation.scatter->sigma_log10, 0.3);
  EXPECT_EQ((*back.separation.covariance)[0][1], 5e-3);
  EXPECT_FALSE(back.radial_crack.scatter);
  const FatigueCard bundled = load_card(std::string(FITLIB_SOURCE_DIR) + "/datasets/cards/fatigue-fritzson-1988.json");
  EXPECT_FALSE(bundled.separation.scatter || bundled.separation.covariance);
  auto j = card_to_json(c);
  j["modes"]["separation"]["covariance"]["matrix"][0][1] = 1.0;  // no longer symmetric
  try {
    card_from_json(j, "mem");
    FAIL() << "an unsymmetric covariance was read";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("modes.separation.covariance.matrix"), std::string::npos) << e.what();
  }
  j = card_to_json(c);
  j["modes"]["separation"]["scatter"]["distribution"] = "weibull";
  EXPECT_THROW(card_from_json(j, "mem"), core::InputError);
}

// [life] uncertainty = "constants+cards" (docs/thermal.md §7): the draws' lives convolved with the
// constants' t. Draws all at the law's life give the constants' interval; a law without covariance gives
// the cards' interval.
TEST(LifeDistribution, CombinedIntervalWithOneSourceOffIsTheOtherSourcesInterval) {
  const LifeLaw law = law_with_scatter(0.3, 1.0);
  const ModeLife m = mode_life(law, {1.5, 0.9, 1.1}, 10.0);
  auto d = *mode_distribution(m, law, 90.0, 80.0, 3600.0);
  add_cards_interval(d, std::vector<double>(20, m.life_cycles), {});
  add_combined_interval(d, std::vector<double>(20, m.life_cycles));
  for (const BLife* b : {&d.b10, &d.b50}) {
    ASSERT_TRUE(b->has_combined_interval);
    EXPECT_NEAR(b->combined_low_cycles / b->low_cycles, 1.0, 1e-12);
    EXPECT_NEAR(b->combined_high_cycles / b->high_cycles, 1.0, 1e-12);
    EXPECT_NEAR(b->combined_low_h / b->low_h, 1.0, 1e-12);
    EXPECT_NEAR(b->combined_high_h / b->high_h, 1.0, 1e-12);
  }
  LifeLaw none = law;
  none.covariance.reset();
  auto c = *mode_distribution(m, none, 90.0, 80.0, 3600.0);
  const std::vector<double> draws{0.6e7, 1.1e7, 0.9e7, 2.0e7, 1.4e7, 0.8e7};
  add_cards_interval(c, draws, {});
  add_combined_interval(c, draws);
  for (const BLife* b : {&c.b10, &c.b50}) {
    EXPECT_EQ(b->combined_low_cycles, b->cards_low_cycles);
    EXPECT_EQ(b->combined_high_cycles, b->cards_high_cycles);
    EXPECT_EQ(b->combined_high_h, b->cards_high_h);
  }
}

// Normal constants' error (no dof) and draws at the normal's quantiles: the variances add, so the
// combined 90 % interval of log10 life is ±1.6449 √(s_cards² + s_constants²) about the law's life.
TEST(LifeDistribution, CombinedIntervalAddsTheVariancesOfNormalSources) {
  LifeLaw law = law_with_scatter(0.3, 1.0);
  law.scatter->dof = 0;
  const ModeLife m = mode_life(law, {1.5, 0.9, 1.1}, 10.0);
  for (double ratio : {1.0, 2.0}) {
    auto d = *mode_distribution(m, law, 90.0, 80.0, 3600.0);
    const double sc = d.constants_sd_log10, sy = ratio * sc;
    ASSERT_GT(sc, 0.01);
    std::vector<double> draws;
    const int J = 4000;
    for (int j = 0; j < J; ++j)
      draws.push_back(m.life_cycles *
                      std::pow(10.0, sy * boost::math::quantile(boost::math::normal(), (j + 0.5) / J)));
    add_cards_interval(d, draws, {});
    add_combined_interval(d, draws);
    const double z95 = 1.6448536269514722, half = z95 * std::sqrt(sy * sy + sc * sc);
    for (const BLife* b : {&d.b10, &d.b50}) {
      EXPECT_NEAR(std::log10(b->combined_high_cycles / b->cycles), half, 2e-3 * half) << ratio;
      EXPECT_NEAR(std::log10(b->cycles / b->combined_low_cycles), half, 2e-3 * half) << ratio;
      EXPECT_NEAR(std::log10(b->high_cycles / b->cycles), z95 * sc, 1e-9);  // the constants' alone
    }
  }
}

// Unbounded draws add no mass below any life: with 9 of 10 unbounded the 95th percentile is unbounded.
TEST(LifeDistribution, CombinedIntervalOfUnboundedDraws) {
  const LifeLaw law = law_with_scatter(0.3, 1.0);
  const ModeLife m = mode_life(law, {1.5, 0.9, 1.1}, 10.0);
  auto d = *mode_distribution(m, law, 90.0, 80.0, 3600.0);
  std::vector<double> draws(10, HUGE_VAL);
  draws[3] = m.life_cycles;
  add_cards_interval(d, draws, {});
  add_combined_interval(d, draws);
  EXPECT_TRUE(std::isinf(d.b50.combined_high_cycles));
  EXPECT_TRUE(std::isfinite(d.b50.combined_low_cycles));
  // 0.1 F_T((x − log10 N)/sd) = 0.05: the 5th percentile is the one finite draw's median, N itself.
  EXPECT_NEAR(d.b50.combined_low_cycles / m.life_cycles, 1.0, 1e-9);
  // life.json writes the unbounded end as null (an unbounded life's spelling), so the file stays finite.
  const auto j = life_distribution_json({d});
  EXPECT_TRUE(j[0]["B50"]["ci90_combined_cycles"][1].is_null());
  EXPECT_TRUE(j[0]["B50"]["ci90_cards_h"][1].is_null());
  EXPECT_NO_THROW(core::require_finite_json(j, "life.json"));
}

}  // namespace
}  // namespace fitlib::fatigue
