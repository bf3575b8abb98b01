#pragma once
// A card's parameter covariance (docs/formats.md §3 fit.covariance) and seeded draws of the card's
// parameters from it (docs/thermal.md §7: [life] uncertainty = "cards"). A draw is
//   x = x̂ + R z,  R Rᵀ = C,  z ~ Normal(0, I),
// in the fitted coordinates (ln p for a positive parameter fitted in logs, so a draw stays positive);
// the parameters without a standard error keep their values.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fitlib/card/card.hpp"

namespace fitlib::card {

struct CardCovariance {
  std::vector<int> index;  // the card's parameter indices it covers
  std::vector<bool> log;   // per entry: the coordinate is ln p
  Eigen::MatrixXd matrix;  // in those coordinates
  bool correlated = true;  // false: built from the standard errors alone (fit.covariance absent)
};

// fit.covariance when the card has it (InputError naming `source` and the key when malformed),
// else a diagonal from the parameters' standard errors (ln p with σ/p for positive values),
// else nullopt.
std::optional<CardCovariance> card_covariance(const Card& card, const std::string& source);

// Seeded draws of a card's parameter values: draw k of stream `stream` is a pure function of
// (seed, stream, k) (core::Rng's platform-independent normals), the same bytes for any number of threads.
class CardSampler {
 public:
  CardSampler(const Card& card, CardCovariance covariance);
  std::vector<double> draw(std::uint64_t seed, std::uint64_t stream, std::uint64_t k) const;
  const CardCovariance& covariance() const { return covariance_; }

 private:
  std::vector<double> values_;
  CardCovariance covariance_;
  Eigen::MatrixXd root_;  // R with R Rᵀ = C (eigen-decomposition: C may be semi-definite)
};

}  // namespace fitlib::card
