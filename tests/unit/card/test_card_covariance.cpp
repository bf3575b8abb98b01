// A card's parameter covariance (fit.covariance): written by the fit in its own coordinates, read
// back, and drawn from with the seeded sampler ([life] uncertainty = "cards", docs/thermal.md §7).
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/card/covariance.hpp"
#include "fitlib/card/from_fit.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/fit/fit.hpp"
#include "unit/fit/fit_testing.hpp"

using namespace fitlib;
using namespace fitlib::fit::testing;

namespace {

card::Card fitted_card() {
  const auto model = prony(3);
  const auto truth = prony_parameters(1.0, {2.0, 5.0, 3.0}, {1e-3, 0.1, 10.0});
  const auto table = synthetic_table(*model, truth, log_frequencies(1e-3, 1e3, 40), 0.02, 11);
  fit::FitOptions o;
  o.backend = fit::Backend::ceres;
  const auto r = fit::fit(model, table, o, &truth);
  return card::card_from_json(card::card_to_json(card::card_from_fit(r, o, table, {"cov", "test", false})));
}

// The diagonal of the stored covariance is the standard errors' square (ln coordinates: (σ/p)²),
// and the fit's correlations are kept (a Prony fit's terms are correlated).
TEST(CardCovariance, FitWritesItsCovarianceAndTheDiagonalIsTheStandardErrors) {
  const card::Card c = fitted_card();
  ASSERT_TRUE(c.fit.contains("covariance"));
  const auto cov = card::card_covariance(c, "card");
  ASSERT_TRUE(cov && cov->correlated);
  int with_error = 0;
  for (const auto& p : c.parameters) with_error += p.std_error.has_value();
  ASSERT_EQ(static_cast<int>(cov->index.size()), with_error);
  double largest_correlation = 0.0;
  for (std::size_t a = 0; a < cov->index.size(); ++a) {
    const auto& p = c.parameters[cov->index[a]];
    const double sd = std::sqrt(cov->matrix(a, a)) * (cov->log[a] ? p.value : 1.0);
    EXPECT_NEAR(sd, *p.std_error, 1e-9 * *p.std_error);
    for (std::size_t b = 0; b < a; ++b)
      largest_correlation = std::max(largest_correlation, std::abs(cov->matrix(a, b)) /
                                                              std::sqrt(cov->matrix(a, a) * cov->matrix(b, b)));
  }
  EXPECT_GT(largest_correlation, 0.1);
}

// 20000 draws: their covariance in the card's coordinates is the card's (to the sampling error),
// their mean the card's values; draw k is a pure function of (seed, stream, k).
TEST(CardCovariance, DrawsHaveTheCardsCovarianceAndAreSeeded) {
  const card::Card c = fitted_card();
  const card::CardSampler sampler(c, *card::card_covariance(c, "card"));
  const auto& cov = sampler.covariance();
  const auto n = static_cast<Eigen::Index>(cov.index.size());
  const int draws = 20000;
  Eigen::MatrixXd x(draws, n);
  for (int k = 0; k < draws; ++k) {
    const auto v = sampler.draw(5, 1, k);
    for (Eigen::Index a = 0; a < n; ++a) {
      const double p = v[cov.index[a]], p0 = c.parameters[cov.index[a]].value;
      x(k, a) = cov.log[a] ? std::log(p / p0) : p - p0;
    }
  }
  const Eigen::RowVectorXd mean = x.colwise().mean();
  const Eigen::MatrixXd centred = x.rowwise() - mean;
  const Eigen::MatrixXd sample = centred.transpose() * centred / (draws - 1);
  for (Eigen::Index a = 0; a < n; ++a) {
    const double sd = std::sqrt(cov.matrix(a, a));
    EXPECT_NEAR(mean[a], 0.0, 5.0 * sd / std::sqrt(draws));
    for (Eigen::Index b = 0; b < n; ++b)  // sampling error of a covariance: ~ sd_a sd_b √(2/n)
      EXPECT_NEAR(sample(a, b), cov.matrix(a, b), 5.0 * sd * std::sqrt(cov.matrix(b, b)) * std::sqrt(2.0 / draws));
  }
  EXPECT_EQ(sampler.draw(5, 1, 17), sampler.draw(5, 1, 17));
  EXPECT_NE(sampler.draw(5, 1, 17), sampler.draw(6, 1, 17));
  EXPECT_NE(sampler.draw(5, 1, 17), sampler.draw(5, 2, 17));
}

TEST(CardCovariance, StandardErrorsAloneGiveADiagonalAndBadMatricesAreRefused) {
  card::Card c = fitted_card();
  c.fit.erase("covariance");
  const auto diagonal = card::card_covariance(c, "card");
  ASSERT_TRUE(diagonal);
  EXPECT_FALSE(diagonal->correlated);
  EXPECT_EQ(diagonal->matrix, Eigen::MatrixXd(diagonal->matrix.diagonal().asDiagonal()));
  for (auto& p : c.parameters) p.std_error.reset();
  EXPECT_FALSE(card::card_covariance(c, "card"));
  auto refused = [&](nlohmann::json cov, const std::string& key) {
    c.fit["covariance"] = cov;
    try {
      card::card_covariance(c, "x.json");
      ADD_FAILURE() << cov.dump();
    } catch (const core::InputError& e) {
      EXPECT_EQ(e.key(), key) << e.what();
    }
  };
  refused({{"parameters", {"G_1"}}, {"coordinates", {"ln"}}, {"matrix", {{1.0, 2.0}}}}, "fit.covariance.matrix");
  refused({{"parameters", {"nope"}}, {"coordinates", {"ln"}}, {"matrix", {{1.0}}}}, "fit.covariance.parameters");
  refused({{"parameters", {"G_1", "G_2"}}, {"coordinates", {"ln", "ln"}}, {"matrix", {{1.0, 0.5}, {0.4, 1.0}}}},
          "fit.covariance.matrix");
  refused({{"parameters", {"G_1"}}, {"coordinates", {"log"}}, {"matrix", {{1.0}}}}, "fit.covariance.coordinates");
  c.fit["covariance"] = {{"parameters", {"G_1", "G_2"}}, {"coordinates", {"ln", "ln"}}, {"matrix", {{1.0, 2.0}, {2.0, 1.0}}}};
  EXPECT_THROW(card::CardSampler(c, *card::card_covariance(c, "x.json")), core::InputError);  // indefinite
}

}  // namespace
