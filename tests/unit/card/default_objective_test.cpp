// The default objective of --terms auto comes from the data (issue 35, item 1) and the verdict
// catches bias (item 2): on Kramers–Kronig consistent data of known truth both moduli count and
// the card follows the noise-free curve between the points; on pyvisco's master (not consistent)
// E′ leads and the verdict says where and by how much E″ is given up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../fit/fit_testing.hpp"
#include "fitlib/card/fit_card.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "known_truth.hpp"

namespace fitlib {
namespace {

using card::testing::HeldOut;
using card::testing::Truth;
using card::testing::held_out;
using card::testing::smooth_truth;

card::FitCardOptions auto_options() {
  card::FitCardOptions o;
  o.model = "prony";
  o.terms = "auto";
  o.model_options = {{"temperature_law", "none"}, {"reference_C", 23.0}};
  o.provenance = {"default-objective", "test", false};
  return o;
}

bool any_contains(const std::vector<std::string>& v, const std::string& what) {
  return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.find(what) != std::string::npos; });
}

// 1 % noise on E′ and E″, 8–10 decades at 10 points per decade, five seeds: the default card's
// held-out rms log10 against the noise-free curve is ≤ 0.0015 (E′) and ≤ 0.0035 (E″), both moduli
// count, and the verdict finds no bias.
constexpr int kPerDecade = 20;  // points per decade of the synthetic tables

TEST(DefaultObjective, ConsistentDataOfKnownTruthCountBothModuli) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const double decades = 8.0 + (seed % 3);
    const Truth t = smooth_truth(static_cast<int>(decades) + 2, 1e-5 / (2.0 * M_PI), seed);
    const auto f = fit::testing::log_frequencies(1e-4, 1e-4 * std::pow(10.0, decades), kPerDecade * static_cast<int>(decades) + 1);
    const auto table = fit::testing::synthetic_table(*t.model, t.p, f, 0.01, 100 + seed);
    const card::FitCardResult r = card::fit_card(table, auto_options());
    const HeldOut h = held_out(r.result, t, f);
    card::FitCardOptions smooth = auto_options();
    smooth.term.compact.enabled = false;
    const HeldOut hs = held_out(card::fit_card(table, smooth).result, t, f);
    std::printf("  without the term economy: E' %.5f E'' %.5f\n", hs.storage, hs.loss);
    std::printf("seed %d, %.0f decades: %zu terms, held-out rms log10 E' %.5f, E'' %.5f, weights %g:%g\n", int(seed),
                decades, r.result.values.size() / 2, h.storage, h.loss, r.card.fit["weights"]["storage"].get<double>(),
                r.card.fit["weights"]["loss"].get<double>());
    EXPECT_LE(h.storage, 0.0015) << "seed " << seed;
    EXPECT_LE(h.loss, 0.0035) << "seed " << seed;
    EXPECT_EQ(r.card.fit["weights"]["storage"].get<double>(), 1.0) << "seed " << seed;
    EXPECT_TRUE(any_contains(r.result.messages, "both moduli count")) << "seed " << seed;
    EXPECT_FALSE(any_contains(r.warnings, "biased")) << "seed " << seed;
  }
}

// The equal-ripple placement of the term economy (an option; docs/decisions.md "Term economy: the
// equal-ripple placement, behind an option"), with the tan δ check on and off, keeps the bars on
// the same data of known truth at 20 and 10 points per decade (seed 1 at 10 per decade misses the
// E′ bar with or without it, as the default does: docs/fitting.md "Default objective").
TEST(DefaultObjective, EqualRippleEconomyKeepsTheKnownTruthBars) {
  for (int per_decade : {kPerDecade, 10})
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      const double decades = 8.0 + (seed % 3);
      const Truth t = smooth_truth(static_cast<int>(decades) + 2, 1e-5 / (2.0 * M_PI), seed);
      const auto f = fit::testing::log_frequencies(1e-4, 1e-4 * std::pow(10.0, decades), per_decade * static_cast<int>(decades) + 1);
      const auto table = fit::testing::synthetic_table(*t.model, t.p, f, 0.01, 100 + seed);
      const HeldOut d = held_out(card::fit_card(table, auto_options()).result, t, f);
      for (const double tan_delta_tolerance : {0.02, double(INFINITY)}) {
        card::FitCardOptions o = auto_options();
        o.term.compact.equal_ripple = true;
        o.term.compact.tan_delta_tolerance = tan_delta_tolerance;
        const card::FitCardResult r = card::fit_card(table, o);
        const HeldOut h = held_out(r.result, t, f);
        std::printf("%d per decade, seed %d: %zu terms, held-out E' %.5f E'' %.5f (default %.5f %.5f)\n", per_decade,
                    int(seed), r.result.values.size() / 2, h.storage, h.loss, d.storage, d.loss);
        const bool known_miss = per_decade == 10 && seed == 1;
        EXPECT_LE(h.storage, known_miss ? 1.05 * d.storage : 0.0015) << per_decade << " per decade, seed " << seed;
        EXPECT_LE(h.loss, 0.0035) << per_decade << " per decade, seed " << seed;
        EXPECT_LE(r.result.values.size() / 2, 10u) << per_decade << " per decade, seed " << seed;
      }
    }
}

// pyvisco's master is not Kramers–Kronig consistent: E′ leads with the weight it had, its figures
// stay (Trust.DefaultFitOfPyviscoMasterBeatsPyviscoAndAnsysOnEveryFigure), and the verdict says
// how much E″ is given up and where.
TEST(DefaultObjective, InconsistentPyviscoMasterKeepsStorageFirstAndSaysWhatLossGivesUp) {
  const auto master = fit::testing::read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  const card::FitCardResult r = card::fit_card(master, auto_options());
  EXPECT_EQ(r.card.fit["weights"]["storage"].get<double>(), fit::kSpectrumStorageWeight);
  EXPECT_NEAR(r.result.metrics.rms_log10_storage, 0.0093, 0.0005);
  EXPECT_TRUE(any_contains(r.warnings, "not Kramers-Kronig consistent: with both moduli counting"));
  EXPECT_TRUE(any_contains(r.warnings, "E'' is given up"));
}

// The README tour's hand-typed table (7 points, 0.1–100 Hz): with E′ first all 7 G″ points came
// out 8–18 % low under "within the thresholds". Now both moduli count and G″ is not biased; with
// the old weights the bias check says so.
TEST(DefaultObjective, ReadmeTourTableIsNotLowOnLossAndBiasIsCaught) {
  const double rows[][3] = {{0.1, 2.0, 0.15}, {0.3, 2.1, 0.25}, {1, 2.3, 0.38}, {3, 2.6, 0.50},
                            {10, 3.0, 0.52},  {30, 3.3, 0.45},  {100, 3.5, 0.35}};
  data::DynamicTestTable table;
  int line = 1;
  for (const auto& r : rows) {
    data::DynamicTestRow row;
    row.condition.mode = model::TestMode::shear;
    row.condition.frequency_Hz = r[0];
    row.condition.temperature_C = 23.0;
    row.storage_MPa = r[1];
    row.loss_MPa = r[2];
    row.source_file = "tour";
    row.source_line = ++line;
    table.rows.push_back(row);
  }
  const card::FitCardResult r = card::fit_card(table, auto_options());
  double worst_low = 0.0;
  for (const auto& row : table.rows)
    worst_low = std::min(worst_low, r.result.model->moduli(r.result.values.data(), row.condition).loss / row.loss_MPa - 1.0);
  std::printf("tour table: worst G'' %.1f %%, weights %g:%g\n", 100.0 * worst_low,
              r.card.fit["weights"]["storage"].get<double>(), r.card.fit["weights"]["loss"].get<double>());
  EXPECT_GT(worst_low, -0.08);
  EXPECT_FALSE(any_contains(r.warnings, "biased"));
  card::FitCardOptions old = auto_options();
  old.objective_given = true;
  old.fit.residual = fit::kSpectrumResidual;
  old.fit.storage_weight = fit::kSpectrumStorageWeight;
  EXPECT_TRUE(any_contains(card::fit_card(table, old).warnings, "biased on the loss modulus"));
}


// Kramers–Kronig ranges (docs/decisions.md "Kramers–Kronig inconsistent ranges"): consistent
// data of known truth have none, in the verdict and in the card; a loss band multiplied by 2.5
// over two decades of otherwise consistent data is found there and nowhere else.
TEST(KramersKronigRanges, ConsistentDataOfKnownTruthHaveNone) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Truth t = smooth_truth(10, 1e-5 / (2.0 * M_PI), seed);
    const auto f = fit::testing::log_frequencies(1e-4, 1e4, kPerDecade * 8 + 1);
    const card::FitCardResult r = card::fit_card(fit::testing::synthetic_table(*t.model, t.p, f, 0.01, 200 + seed), auto_options());
    EXPECT_TRUE(r.result.quality.kramers_kronig_ranges_Hz.empty()) << "seed " << seed;
    EXPECT_FALSE(r.card.fit["quality"].contains("kramers_kronig_inconsistent_Hz")) << "seed " << seed;
    EXPECT_FALSE(any_contains(r.warnings, "not Kramers-Kronig consistent")) << "seed " << seed;
  }
}

TEST(KramersKronigRanges, InjectedLossBandIsFoundWhereItIs) {
  const double band_lo = 1.0, band_hi = 100.0;  // Hz: E'' × 2.5 there
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Truth t = smooth_truth(10, 1e-5 / (2.0 * M_PI), seed);
    const auto f = fit::testing::log_frequencies(1e-4, 1e4, kPerDecade * 8 + 1);
    auto table = fit::testing::synthetic_table(*t.model, t.p, f, 0.01, 300 + seed);
    for (auto& row : table.rows)
      if (row.condition.frequency_Hz >= band_lo && row.condition.frequency_Hz <= band_hi) row.loss_MPa *= 2.5;
    const card::FitCardResult r = card::fit_card(table, auto_options());
    const auto& ranges = r.result.quality.kramers_kronig_ranges_Hz;
    ASSERT_EQ(ranges.size(), 1u) << "seed " << seed;
    std::printf("seed %d: inconsistent %.3g to %.3g Hz (injected %.3g to %.3g)\n", int(seed), ranges[0].first,
                ranges[0].second, band_lo, band_hi);
    EXPECT_GE(ranges[0].first, band_lo / 1.01) << "seed " << seed;
    EXPECT_LE(ranges[0].second, band_hi * 1.01) << "seed " << seed;
    EXPECT_GE(std::log10(ranges[0].second / ranges[0].first), 1.5) << "seed " << seed;  // most of the band
    EXPECT_EQ(r.card.fit["quality"]["kramers_kronig_inconsistent_Hz"].size(), 1u) << "seed " << seed;
  }
}

// pyvisco's master: its E'' plateau below the transition is what no spectrum under its E' can
// hold; above the transition the card's loss is within a factor 1.5 of the data (the range once
// spanned the whole data, 1e-12 to 1e14 Hz).
TEST(KramersKronigRanges, PyviscoMasterIsInconsistentBelowTheTransitionOnly) {
  const auto master = fit::testing::read_pyvisco("datasets/materials/pyvisco-freq-master.csv");
  const auto ranges = card::fit_card(master, auto_options()).result.quality.kramers_kronig_ranges_Hz;
  ASSERT_FALSE(ranges.empty());
  EXPECT_NEAR(std::log10(ranges.front().first), -12.0, 0.01);
  for (const auto& [lo, hi] : ranges) {
    std::printf("pyvisco master: inconsistent %.3g to %.3g Hz\n", lo, hi);
    EXPECT_LT(hi, 10.0);
  }
}

}  // namespace
}  // namespace fitlib
