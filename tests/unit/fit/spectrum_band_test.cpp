// The confidence band of a smooth-spectrum card (docs/decisions.md "Confidence band under the
// smoothness prior"): smooth over frequency on pyvisco's master where the bare covariance spikes
// at every grid τ, and covering the noise-free curve of synthetic data of known truth.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

#include "fit_testing.hpp"
#include "fitlib/fit/spectrum.hpp"

namespace fitlib {
namespace {

std::function<model::ModelPtr(int)> prony_of(const std::string& mode) {
  return [mode](int n) { return fit::testing::prony(n, mode); };
}

fit::FitOptions spectrum_options() {
  fit::FitOptions o;
  o.residual = fit::kSpectrumResidual;
  o.storage_weight = fit::kSpectrumStorageWeight;
  return o;
}

// Local extrema of the band's relative half-width ln(high/low)/2 of E″ over its frequencies: one
// per grid τ when each term carries its own variance.
int loss_width_extrema(const fit::ConfidenceBand& band) {
  std::vector<double> w;
  for (const auto& b : band.points) w.push_back(0.5 * std::log(b.loss_high / b.loss_low));
  int extrema = 0;
  for (std::size_t k = 1; k + 1 < w.size(); ++k)
    if ((w[k] - w[k - 1]) * (w[k + 1] - w[k]) < 0.0) ++extrema;
  return extrema;
}

TEST(SpectrumBand, SmoothOnPyviscoMasterWhereTheBareCovarianceSpikesAtEveryTau) {
  const auto table = fit::testing::read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  const fit::SpectrumFit s = fit::fit_spectrum(prony_of("uniaxial"), table, spectrum_options());
  ASSERT_GT(s.result.band.points.size(), 500u);  // 20 per decade over 26 decades
  // The same card assessed with the bare covariance: NNLS from its own values, no prior.
  fit::FitOptions bare = spectrum_options();
  bare.backend = fit::Backend::nnls;
  bare.polish = false;
  const fit::FitResult plain = fit::fit(s.result.model, table, bare, &s.result.values);
  const int smooth = loss_width_extrema(s.result.band), spiky = loss_width_extrema(plain.band);
  std::printf("E'' band width extrema: %d under the prior, %d bare (%d grid terms)\n", smooth, spiky, s.grid_terms);
  EXPECT_LE(smooth, 12);
  EXPECT_GE(spiky, s.grid_terms / 2);
  for (const auto& b : s.result.band.points) {
    EXPECT_LE(b.loss_low, b.loss);
    EXPECT_GE(b.loss_high, b.loss);
  }
}

// Shares of the band's frequencies where the noise-free truth lies inside the E′ and E″ bands.
struct Coverage {
  double storage = 0.0, loss = 0.0;
};
Coverage coverage(const fit::ConfidenceBand& band, const model::Model& truth, const std::vector<double>& p) {
  Coverage c;
  for (const auto& b : band.points) {
    model::TestCondition at = band.condition;
    at.frequency_Hz = b.frequency_Hz;
    const auto m = truth.moduli(p.data(), at);
    c.storage += m.storage >= b.storage_low && m.storage <= b.storage_high;
    c.loss += m.loss >= b.loss_low && m.loss <= b.loss_high;
  }
  c.storage /= band.points.size();
  c.loss /= band.points.size();
  return c;
}

// 1 % noise on a smooth 10-term truth over 8 decades, five seeds: the 95 % bands hold the
// noise-free E′ and E″ at most of their frequencies (the prior's band carries no bias term: its
// coverage is measured, not assumed).
TEST(SpectrumBand, CoversTheNoiseFreeCurveOfKnownTruth) {
  Coverage mean;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    core::Rng rng(seed);
    std::vector<double> moduli, times;
    const double centre = 3.0 + 3.0 * rng.uniform();
    for (int i = 0; i < 10; ++i) {
      moduli.push_back(40.0 * std::exp(-0.5 * std::pow((i - centre) / 2.5, 2)) + 0.5);
      times.push_back(1e-5 / (2.0 * M_PI) * std::pow(10.0, i));
    }
    const auto truth = fit::testing::prony(10);
    const auto p = fit::testing::prony_parameters(1.0, moduli, times);
    const auto f = fit::testing::log_frequencies(1e-4, 1e4, 161);
    const auto table = fit::testing::synthetic_table(*truth, p, f, 0.01, 50 + seed);
    const fit::SpectrumFit s = fit::fit_spectrum(prony_of("shear"), table, spectrum_options());
    fit::FitOptions bare = spectrum_options();
    bare.backend = fit::Backend::nnls;
    bare.polish = false;
    const Coverage prior = coverage(s.result.band, *truth, p);
    const Coverage plain = coverage(fit::fit(s.result.model, table, bare, &s.result.values).band, *truth, p);
    std::printf("seed %d: truth inside the band E' %.1f %%, E'' %.1f %% (bare covariance: %.1f %%, %.1f %%)\n",
                int(seed), 100.0 * prior.storage, 100.0 * prior.loss, 100.0 * plain.storage, 100.0 * plain.loss);
    EXPECT_GE(prior.storage, 0.7) << "seed " << seed;
    EXPECT_GE(prior.loss, 0.7) << "seed " << seed;
    mean.storage += prior.storage / 5.0;
    mean.loss += prior.loss / 5.0;
  }
  EXPECT_GE(mean.storage, 0.85);
  EXPECT_GE(mean.loss, 0.85);
}

}  // namespace
}  // namespace fitlib
