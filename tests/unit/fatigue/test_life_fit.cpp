#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/fatigue/life.hpp"
#include "fitlib/fatigue/life_fit.hpp"
#include "csv_error.hpp"

namespace fitlib::fatigue {
namespace {

// Synthetic cases of known constants: two monitored points per case with random peaks, random
// temperatures, lives from (6.31) at the design point, times exp(noise) in log10.
std::vector<ObservedLife> synthetic(Mode mode, const LifeLaw& truth, int count, double noise,
                                    std::uint64_t seed, bool vary_temperature = true) {
  core::Rng rng(seed);
  std::vector<ObservedLife> out;
  for (int k = 0; k < count; ++k) {
    ObservedLife c;
    c.name = "case" + std::to_string(k);
    c.mode = mode;
    c.temperature_C = vary_temperature ? rng.uniform(60.0, 120.0) : 90.0;
    const double level = truth.sigma0_MPa * rng.uniform(0.05, 0.4);
    for (int p = 0; p < 2; ++p) {
      std::vector<double> peaks;
      const int m = 1 + static_cast<int>(rng.uniform(0.0, 4.0));
      for (int i = 0; i < m; ++i) peaks.push_back(level * rng.uniform(0.3, 1.0));
      c.point_peaks_MPa.push_back(peaks);
    }
    c.observed_cycles = 1.0;  // placeholder for the prediction below
    c.observed_cycles = std::pow(10.0, predicted_log10_life(c, truth, 80.0) + noise * rng.normal());
    out.push_back(c);
  }
  return out;
}

TEST(LifeFit, RecoversKnownConstantsFromExactLives) {
  const LifeLaw truth{4.21028, 11.69, 0.1466, std::nullopt};
  auto cases = synthetic(Mode::separation, truth, 12, 0.0, 5);
  // Cases of the other mode are ignored by this mode's fit.
  auto other = synthetic(Mode::radial_crack, LifeLaw{104.218, 4.423, 0.02897, std::nullopt}, 5, 0.0, 6);
  cases.insert(cases.end(), other.begin(), other.end());
  LifeFitOptions o;
  o.start = LifeLaw{8.0, 6.0, 0.05, std::nullopt};
  const LifeFitResult r = fit_life_law(cases, Mode::separation, o);
  EXPECT_EQ(r.cases, 12);
  EXPECT_NEAR(r.law.sigma0_MPa / truth.sigma0_MPa, 1.0, 1e-7);
  EXPECT_NEAR(r.law.n / truth.n, 1.0, 1e-7);
  EXPECT_NEAR(r.law.b_per_C / truth.b_per_C, 1.0, 1e-7);
  EXPECT_LT(r.rms_log10_error, 1e-8);
}

// A runout (a test stopped without failing) bounds the life from below. Runouts the truth lets live
// past their stop leave the fit of exact failures exact; a runout stopped later than the truth's
// life pulls the law towards it (its prediction rises) and is named as violated; a mode with
// runouts only keeps the start law, and the runouts that refute it are a warning.
TEST(LifeFit, RunoutsBoundTheLifeFromBelowOnly) {
  const LifeLaw truth{4.21028, 11.69, 0.1466, std::nullopt};
  std::vector<ObservedLife> cases = synthetic(Mode::separation, truth, 12, 0.0, 5);
  auto runouts = synthetic(Mode::separation, truth, 6, 0.0, 8);
  for (ObservedLife& r : runouts) r.runout = true, r.name = "runout-" + r.name, r.observed_cycles /= 3.0;
  cases.insert(cases.end(), runouts.begin(), runouts.end());
  LifeFitOptions o;
  o.start = LifeLaw{8.0, 6.0, 0.05, std::nullopt};
  const LifeFitResult kept = fit_life_law(cases, Mode::separation, o);
  EXPECT_EQ(kept.cases, 12);
  EXPECT_EQ(kept.runouts, 6);
  EXPECT_NEAR(kept.law.n / truth.n, 1.0, 1e-7);
  EXPECT_NEAR(kept.law.sigma0_MPa / truth.sigma0_MPa, 1.0, 1e-7);
  EXPECT_LT(kept.rms_log10_error, 1e-8);
  EXPECT_TRUE(kept.violated_runouts.empty());
  // One runout stopped 30× beyond the truth's life: the fit moves towards it, and names it.
  cases.back().observed_cycles *= 3.0 * 30.0;
  const LifeFitResult pulled = fit_life_law(cases, Mode::separation, o);
  const double truth_at = predicted_log10_life(cases.back(), truth, 80.0);
  EXPECT_GT(predicted_log10_life(cases.back(), pulled.law, 80.0), truth_at + 0.05);
  EXPECT_LT(predicted_log10_life(cases.back(), pulled.law, 80.0), std::log10(cases.back().observed_cycles));
  ASSERT_EQ(pulled.violated_runouts.size(), 1u);
  EXPECT_EQ(pulled.violated_runouts[0].rfind(cases.back().name + " (predicted ", 0), 0u) << pulled.violated_runouts[0];
  EXPECT_GT(pulled.rms_log10_error, 0.0);
  const LifeCardFit card = fit_life_card(cases, default_card());
  bool said = false;
  for (const auto& w : card.warnings) said |= w.find("runout " + cases.back().name) != std::string::npos;
  EXPECT_TRUE(said);
  // Runouts only: no law to fit (an error for the law, the start kept by the card, a refutation said);
  // no failure in any mode is an input error naming failure_mode.
  std::vector<ObservedLife> only(runouts);
  EXPECT_THROW(fit_life_law(only, Mode::separation, o), core::InputError);
  try {
    fit_life_card(only, default_card());
    ADD_FAILURE() << "runouts alone fitted a card";
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), "failure_mode");
    EXPECT_NE(std::string(e.what()).find("no life test failed (6 runout case(s))"), std::string::npos) << e.what();
  }
  only.push_back(synthetic(Mode::radial_crack, LifeLaw{104.218, 4.423, 0.02897, std::nullopt}, 3, 0.0, 6)[0]);
  only.front().observed_cycles = 1e30;
  const LifeCardFit start_kept = fit_life_card(only, default_card(), HeldConstants{true, true});
  EXPECT_EQ(start_kept.card.separation.n, default_card().separation.n);
  bool refuted = false;
  for (const auto& w : start_kept.warnings)
    refuted |= w.find("the start card's constants say runout " + only.front().name) != std::string::npos;
  EXPECT_TRUE(refuted);
}

// Property over 10 seeds: exact failures plus runouts stopped at random fractions (0.05–1) of the
// truth's lives fit back to the truth exactly, whatever the mix; the runouts are counted, none violated.
TEST(LifeFit, RunoutsBeforeTheTruthsLivesNeverMoveAnExactFit) {
  const LifeLaw truth{104.218, 4.423, 0.02897, std::nullopt};
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    core::Rng rng(100 + seed);
    auto cases = synthetic(Mode::radial_crack, truth, 6 + static_cast<int>(seed), 0.0, seed);
    auto runouts = synthetic(Mode::radial_crack, truth, 1 + static_cast<int>(seed % 5), 0.0, 50 + seed);
    for (ObservedLife& r : runouts) r.runout = true, r.observed_cycles *= rng.uniform(0.05, 1.0);
    cases.insert(cases.end(), runouts.begin(), runouts.end());
    LifeFitOptions o;
    o.start = LifeLaw{50.0, 3.0, 0.0, std::nullopt};
    const LifeFitResult r = fit_life_law(cases, Mode::radial_crack, o);
    EXPECT_EQ(r.runouts, static_cast<int>(runouts.size())) << seed;
    EXPECT_NEAR(r.law.n / truth.n, 1.0, 1e-6) << seed;
    EXPECT_NEAR(r.law.sigma0_MPa / truth.sigma0_MPa, 1.0, 1e-6) << seed;
    EXPECT_TRUE(r.violated_runouts.empty()) << seed;
  }
}

TEST(LifeFit, IntervalsCoverTheTruthWithScatter) {
  const LifeLaw truth{104.218, 4.423, 0.02897, std::nullopt};
  const auto cases = synthetic(Mode::radial_crack, truth, 30, 0.15, 17);
  LifeFitOptions o;
  o.start = LifeLaw{50.0, 3.0, 0.0, std::nullopt};
  const LifeFitResult r = fit_life_law(cases, Mode::radial_crack, o);
  ASSERT_EQ(r.constants.size(), 3u);
  const double t[3] = {truth.sigma0_MPa, truth.n, truth.b_per_C};
  for (int k = 0; k < 3; ++k) {
    const ConstantEstimate& e = r.constants[k];
    ASSERT_TRUE(e.has_interval) << e.name;
    EXPECT_LT(e.ci95_low, t[k]) << e.name;
    EXPECT_GT(e.ci95_high, t[k]) << e.name;
    EXPECT_GT(e.std_error, 0.0);
  }
  EXPECT_NEAR(r.rms_log10_error, 0.15, 0.06);
}

TEST(LifeFit, OneTemperatureHoldsB) {
  const LifeLaw truth{4.21028, 11.69, 0.1466, std::nullopt};
  const auto cases = synthetic(Mode::separation, truth, 8, 0.0, 9, false);
  LifeFitOptions o;
  o.start = LifeLaw{6.0, 9.0, 0.1466, std::nullopt};
  const LifeFitResult r = fit_life_law(cases, Mode::separation, o);
  EXPECT_TRUE(r.constants[2].fixed);
  EXPECT_NE(r.note.find("one temperature"), std::string::npos);
  EXPECT_NEAR(r.law.n / truth.n, 1.0, 1e-7);
  EXPECT_NEAR(r.law.sigma0_MPa / truth.sigma0_MPa, 1.0, 1e-7);
  EXPECT_THROW(fit_life_law(cases, Mode::radial_crack, o), core::InputError);
}

TEST(ObservedLives, ReadsCasesWithSeveralPoints) {
  const std::string text =
      "# observed lives\n"
      "case,failure_mode,temperature_C,observed_h,cycles_per_h,point,peaks_MPa\n"
      "A,separation,90,120,60000,cushion-1,1.2;0.8\n"
      "A,separation,90,120,60000,cushion-2,1.1\n"
      "B,radial_crack,85.5,2000,60000,gap,\"5;4.5;3\"\n";
  const auto cases = parse_observed_lives(text, "lives.csv");
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].point_peaks_MPa.size(), 2u);
  EXPECT_EQ(cases[0].point_peaks_MPa[0], (std::vector<double>{1.2, 0.8}));
  EXPECT_DOUBLE_EQ(cases[0].observed_cycles, 120.0 * 60000.0);
  EXPECT_EQ(cases[1].mode, Mode::radial_crack);
  EXPECT_EQ(cases[1].point_peaks_MPa[0].size(), 3u);
  EXPECT_EQ(cases[1].line, 5);
}

void expect_error(const std::string& text, int line, int column, const std::string& key = "") {
  expect_csv_error(parse_observed_lives, text, line, column, key);
}

TEST(ObservedLives, ErrorsNameLineAndColumn) {
  const std::string head = "case,failure_mode,temperature_C,observed_cycles,peaks_MPa\n";
  expect_error(head + "A,crack,90,1e6,1.0\n", 2, 2, "failure_mode");
  expect_error(head + "A,separation,90,1e6,1.0;x\n", 2, 5);
  expect_error(head + "A,separation,90,-5,1.0\n", 2, 4, "observed_cycles");
  expect_error(head + "A,separation,90,1e6,1.0\nA,separation,91,1e6,2.0\n", 3, 1, "case");
  expect_error(head + "A,separation,90,1e6\n", 2, 5);
  expect_error("case,failure_mode,temperature,observed_cycles,peaks_MPa\n", 1, 3, "temperature");
  expect_error("case,failure_mode,temperature_C,peaks_MPa\n", 1, 0, "observed_cycles");
  expect_error(head, 1, 0);
  // The level of the peaks: a known word, one per case and one per mode.
  const std::string levels = "case,failure_mode,temperature_C,observed_cycles,peaks_MPa,stress_fidelity\n";
  expect_error(levels + "A,separation,90,1e6,1.0,fine\n", 2, 6, "stress_fidelity");
  expect_error(levels + "A,separation,90,1e6,1.0,beam\nA,separation,90,1e6,2.0,elastic\n", 3, 1, "case");
  expect_error(levels + "A,separation,90,1e6,1.0,beam\nB,radial_crack,90,1e6,2.0,elastic\n"
                        "C,separation,90,1e5,2.0,elastic\n", 4, 0, "stress_fidelity");
  expect_error(levels + "A,separation,90,1e6,1.0,\nC,separation,90,1e5,2.0,complete\n", 3, 0, "stress_fidelity");
}

// The runout column: a runout's rows may list both modes' points (one case per mode); a name used
// by a failure and a runout, or a runout that is not 0/1, names its line; the CSV reads back equal.
TEST(ObservedLives, RunoutRowsGiveOneCasePerModeAndReadBack) {
  const std::string text =
      "case,failure_mode,temperature_C,observed_cycles,point,peaks_MPa,runout\n"
      "A,separation,90,1e8,c1,1.2,0\n"
      "R,separation,90,5e9,c1,0.7;0.5,1\n"
      "R,radial_crack,90,5e9,g1,5,1\n"
      "R,radial_crack,90,5e9,g2,4,1\n";
  const auto cases = parse_observed_lives(text, "lives.csv");
  ASSERT_EQ(cases.size(), 3u);
  EXPECT_FALSE(cases[0].runout);
  EXPECT_TRUE(cases[1].runout);
  EXPECT_EQ(cases[1].mode, Mode::separation);
  EXPECT_EQ(cases[2].mode, Mode::radial_crack);
  EXPECT_EQ(cases[2].point_peaks_MPa.size(), 2u);
  const auto back = parse_observed_lives(observed_lives_csv(cases), "back.csv");
  ASSERT_EQ(back.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(back[k].runout, cases[k].runout);
    EXPECT_EQ(back[k].point_peaks_MPa, cases[k].point_peaks_MPa);
  }
  const std::string head = "case,failure_mode,temperature_C,observed_cycles,peaks_MPa,runout\n";
  expect_error(head + "A,separation,90,1e6,1.0,yes\n", 2, 6, "runout");
  expect_error(head + "A,separation,90,1e6,1.0,0\nA,radial_crack,90,1e6,2.0,1\n", 3, 6, "runout");
}

// The fitted law is of its cases' level; a mode without cases keeps the start card's, and a card
// whose modes come from two levels says so.
TEST(ObservedLives, TheFittedLawIsOfItsCasesStressLevel) {
  const std::string text = "case,failure_mode,temperature_C,observed_cycles,peaks_MPa,stress_fidelity\n"
                           "A,separation,90,1e6,1.0,elastic\nB,separation,90,1e5,1.3,elastic\n";
  const auto cases = parse_observed_lives(text, "lives.csv");
  EXPECT_EQ(parse_observed_lives(observed_lives_csv(cases), "again.csv")[1].stress_fidelity, core::Fidelity::elastic);
  const LifeCardFit fit = fit_life_card(cases, default_card());
  EXPECT_EQ(fit.card.separation.stress_fidelity, core::Fidelity::elastic);
  EXPECT_EQ(fit.card.radial_crack.stress_fidelity, core::Fidelity::complete);  // the start's, kept
  EXPECT_TRUE(std::any_of(fit.warnings.begin(), fit.warnings.end(), [](const std::string& w) {
    return w.find("radial_crack constants are of complete-level stresses, its separation constants of "
                  "elastic-level ones") != std::string::npos;
  }));
  // Without the column the level is not stated, and no column is written back.
  const auto unstated = parse_observed_lives("case,failure_mode,temperature_C,observed_cycles,peaks_MPa\n"
                                             "A,separation,90,1e6,1.0\nB,separation,90,1e5,1.3\n", "plain.csv");
  EXPECT_EQ(fit_life_card(unstated, default_card()).card.separation.stress_fidelity, std::nullopt);
  EXPECT_EQ(observed_lives_csv(unstated).find("stress_fidelity"), std::string::npos);
}

}  // namespace
}  // namespace fitlib::fatigue

namespace fitlib::fatigue {
namespace {

// Two bottom points and one cushion point with known σ22 / σ12 signals (1 s spacing).
std::vector<PointHistory> three_points(double scale) {
  std::vector<PointHistory> pts(3);
  const std::vector<std::vector<double>> v = {{0, 30, 0, 12, 0}, {0, 20, 0, 20, 0, 20, 0},
                                              {0, 1.1, 0, 0.6, 0}};
  for (int k = 0; k < 3; ++k) {
    pts[k].name = "p" + std::to_string(k);
    pts[k].role = k < 2 ? Role::bottom : Role::cushion;
    for (std::size_t i = 0; i < v[k].size(); ++i) {
      StressSample s;
      s.t_s = static_cast<double>(i);
      (k < 2 ? s.s22_MPa : s.s12_MPa) = scale * v[k][i];
      pts[k].samples.push_back(s);
    }
  }
  return pts;
}

TEST(ObservedLives, FromStressHistoriesAgreeWithTheLifeReport) {
  // The fit's log-sum-exp life and evaluate_life are two implementations of (6.31).
  const FatigueCard card = default_card();
  LifeConditions c;
  c.temperature_C = 97.0;
  const auto pts = three_points(1.0);
  const LifeReport r = evaluate_life(pts, card, c);
  for (Mode mode : {Mode::radial_crack, Mode::separation}) {
    const ObservedLife o = observed_life("x", mode, 1e6, pts, card, c);
    const double n = r.modes[mode == Mode::radial_crack ? 0 : 1].life_cycles;
    EXPECT_NEAR(predicted_log10_life(o, card.law(mode), card.reference_temperature_C),
                std::log10(n), 1e-12);
  }
}

TEST(ObservedLives, CsvRoundTripAndFitFromHistories) {
  // Lives from a known card for loads 0.6 … 1.5 and temperatures 70 … 110 °C, written to CSV,
  // read back, fitted: the card's mode-1 constants come back.
  const FatigueCard card = default_card();
  std::vector<ObservedLife> cases;
  for (int k = 0; k < 8; ++k) {
    LifeConditions c;
    c.temperature_C = 70.0 + 5.0 * k;
    const auto pts = three_points(0.6 + 0.13 * ((k * 5) % 8));
    const double n = evaluate_life(pts, card, c).modes[0].life_cycles;
    cases.push_back(observed_life("case " + std::to_string(k), Mode::radial_crack, n, pts, card, c));
  }
  const std::string text = observed_lives_csv(cases);
  const auto back = parse_observed_lives(text, "lives.csv");
  ASSERT_EQ(back.size(), cases.size());
  for (std::size_t k = 0; k < cases.size(); ++k) {
    EXPECT_EQ(back[k].point_peaks_MPa, cases[k].point_peaks_MPa);
    EXPECT_EQ(back[k].observed_cycles, cases[k].observed_cycles);
  }
  LifeFitOptions o;
  o.start = LifeLaw{60.0, 3.0, 0.01, std::nullopt};
  const LifeFitResult r = fit_life_law(back, Mode::radial_crack, o);
  EXPECT_NEAR(r.law.sigma0_MPa / 104.218, 1.0, 1e-6);
  EXPECT_NEAR(r.law.n / 4.423, 1.0, 1e-6);
  EXPECT_NEAR(r.law.b_per_C / 0.02897, 1.0, 1e-6);
}

}  // namespace
}  // namespace fitlib::fatigue

namespace fitlib::fatigue {
namespace {

// The card: fitted modes replace the start's law, a mode without cases keeps it and says so;
// lives scattering by more than a factor 3.2 and an undetermined σ0 are warnings.
TEST(LifeCardFit, ReplacesFittedModesKeepsOthersAndWarnsAboutPoorFits) {
  const LifeLaw truth{4.21028, 11.69, 0.1466, std::nullopt};
  FatigueCard start = default_card();
  start.separation = LifeLaw{6.0, 8.0, 0.1, std::nullopt};
  const LifeCardFit exact = fit_life_card(synthetic(Mode::separation, truth, 12, 0.0, 5), start);
  ASSERT_EQ(exact.fits.size(), 1u);
  EXPECT_NEAR(exact.card.separation.n / truth.n, 1.0, 1e-7);
  EXPECT_EQ(exact.card.radial_crack.sigma0_MPa, start.radial_crack.sigma0_MPa);
  ASSERT_EQ(exact.warnings.size(), 1u);
  EXPECT_NE(exact.warnings[0].find("radial_crack: no case failed in this mode"), std::string::npos);
  EXPECT_EQ(exact.card.provenance["life_fit"]["separation"]["cases"], 12);
  EXPECT_TRUE(exact.card.provenance["life_fit"]["separation"]["constants"]["n"].contains("ci95"));
  EXPECT_NO_THROW(card_from_json(card_to_json(exact.card), "fitted"));  // the card reads back

  const LifeCardFit scattered = fit_life_card(synthetic(Mode::separation, truth, 12, 1.0, 5), start);
  bool scatter = false;
  for (const std::string& w : scattered.warnings) scatter = scatter || w.find("scatter around the fit") != std::string::npos;
  EXPECT_TRUE(scatter);
  const LifeCardFit quiet = fit_life_card(synthetic(Mode::separation, truth, 12, 0.1, 5), start);
  EXPECT_EQ(quiet.warnings.size(), 1u);  // only the mode without cases
}

// Lives that do not fall with the stress put n at its bound and σ0 at 10¹⁰⁰ MPa: that mode keeps the
// start card's law and says why; when no mode with cases was fitted, nothing is a result (exit 4).
TEST(LifeCardFit, AFitWithNAtItsBoundKeepsTheStartLawAndNoFitAtAllIsAnError) {
  auto make = [](const std::string& name, Mode mode, double peak_MPa, double cycles) {
    ObservedLife c;
    c.name = name, c.mode = mode, c.temperature_C = 80.0, c.observed_cycles = cycles;
    c.point_peaks_MPa = {{peak_MPa}};
    return c;
  };
  const FatigueCard start = default_card();
  const std::vector<ObservedLife> rising = {make("a", Mode::radial_crack, 1.0, 1e6), make("b", Mode::radial_crack, 2.0, 1e7),
                                            make("c", Mode::radial_crack, 3.0, 3e7)};
  std::vector<ObservedLife> cases = rising;
  for (double p : {1.0, 1.5, 2.0}) cases.push_back(make("s" + std::to_string(p), Mode::separation, p, 1e8 * std::pow(p, -10.0)));
  const LifeCardFit fit = fit_life_card(cases, start);
  ASSERT_EQ(fit.fits.size(), 2u);
  EXPECT_NE(fit.fits[0].rejected.find("n went to its bound 0.1"), std::string::npos) << fit.fits[0].rejected;
  EXPECT_EQ(fit.card.radial_crack.sigma0_MPa, start.radial_crack.sigma0_MPa);
  EXPECT_EQ(fit.card.radial_crack.n, start.radial_crack.n);
  EXPECT_TRUE(fit.fits[1].rejected.empty());
  EXPECT_NEAR(fit.card.separation.n, 10.0, 1e-6);
  EXPECT_TRUE(fit.card.provenance["life_fit"]["radial_crack"].contains("rejected"));
  bool said = false;
  for (const std::string& w : fit.warnings) said = said || w.find("radial_crack: not fitted") != std::string::npos;
  EXPECT_TRUE(said);
  EXPECT_THROW(fit_life_card(rising, start), core::NumericalError);
  // Lives scattered by a factor 10 over 60–120 °C hide the temperature's effect: b's interval reaches zero.
  const LifeCardFit noisy = fit_life_card(synthetic(Mode::separation, LifeLaw{4.21028, 11.69, 0.1466, std::nullopt}, 5, 1.0, 3), start);
  ASSERT_TRUE(noisy.fits[0].constants[2].has_interval);
  EXPECT_LE(noisy.fits[0].constants[2].ci95_low, 0.0);
  said = false;
  for (const std::string& w : noisy.warnings) said = said || w.find("separation: b's 95 % interval") != std::string::npos;
  EXPECT_TRUE(said);
  // Four hand-typed separation tests at 10–30 N·m (the light drive's beam-level peaks, 1 degree of
  // freedom): n 9.59 [−4.13, 23.3], a negative exponent inside the interval, is a warning.
  const auto hand = parse_observed_lives(
      "case,failure_mode,temperature_C,observed_cycles,peaks_MPa\n"
      "a,separation,80,309293303.1883142,1.3434475442517084;1.310205703525924;0.3627259323172915\n"
      "b,separation,80,1237173212.7532568,1.029668455631264;1.1658418209933423;0.4586221959454639\n"
      "c,separation,80,55672794.57389656,1.5789611244872044;1.4896115714078948\n"
      "d,separation,100,185575981.9129885,1.2224305588719562;1.180017400496983;0.36272593231728417\n", "hand.csv");
  const LifeCardFit weak = fit_life_card(hand, start);
  const ConstantEstimate& n = weak.fits[0].constants[1];
  ASSERT_TRUE(n.has_interval);
  EXPECT_NEAR(n.value, 9.59, 0.01);
  EXPECT_LT(n.ci95_low, 0.0);
  said = false;
  for (const std::string& w : weak.warnings) said = said || w.find("separation: n's 95 % interval") != std::string::npos;
  EXPECT_TRUE(said);
  const LifeCardFit exact = fit_life_card(synthetic(Mode::separation, LifeLaw{4.21028, 11.69, 0.1466, std::nullopt}, 5, 0.0, 3), start);
  for (const std::string& w : exact.warnings) EXPECT_EQ(w.find("n's 95 % interval"), std::string::npos) << w;
}

// No more free constants than cases: one case fits σ0 alone (n, b held), two fit σ0 and n; either
// passes through its cases exactly, which is a warning, not a result to trust. --fix-n holds n.
TEST(LifeCardFit, FewCasesHoldConstantsAndAnExactFitIsAWarning) {
  const LifeLaw truth{4.21028, 11.69, 0.1466, std::nullopt};
  FatigueCard start = default_card();
  start.separation = LifeLaw{6.0, 8.0, 0.1, std::nullopt};
  const auto cases = synthetic(Mode::separation, truth, 4, 0.0, 5);
  auto warned_exact = [](const LifeCardFit& f) {
    for (const std::string& w : f.warnings)
      if (w.find("passes through every case") != std::string::npos) return true;
    return false;
  };
  const LifeCardFit one = fit_life_card({cases[0]}, start);
  EXPECT_EQ(one.card.separation.n, start.separation.n);
  EXPECT_EQ(one.card.separation.b_per_C, start.separation.b_per_C);
  EXPECT_NEAR(predicted_log10_life(cases[0], one.card.separation, 80.0), std::log10(cases[0].observed_cycles), 1e-9);
  EXPECT_TRUE(one.fits[0].constants[1].fixed);
  EXPECT_NE(one.fits[0].note.find("one case fixes sigma0 alone"), std::string::npos);
  EXPECT_TRUE(warned_exact(one));

  const LifeCardFit two = fit_life_card({cases[0], cases[1]}, start);  // two temperatures, b still held
  EXPECT_NE(two.card.separation.n, start.separation.n);
  EXPECT_EQ(two.card.separation.b_per_C, start.separation.b_per_C);
  EXPECT_NE(two.fits[0].note.find("two cases cannot fix three constants"), std::string::npos);
  EXPECT_TRUE(warned_exact(two));

  const std::vector<ObservedLife> three(cases.begin(), cases.begin() + 3);
  EXPECT_TRUE(warned_exact(fit_life_card(three, start)));  // three free constants through three cases
  EXPECT_FALSE(warned_exact(fit_life_card(cases, start)));
  const LifeCardFit held = fit_life_card(three, start, {true, false});
  EXPECT_EQ(held.card.separation.n, start.separation.n);
  EXPECT_FALSE(warned_exact(held));  // σ0 and b from three cases leave one residual
  EXPECT_TRUE(held.fits[0].constants[1].fixed);
  EXPECT_FALSE(held.fits[0].constants[1].has_interval);
  EXPECT_TRUE(held.fits[0].constants[2].has_interval);  // b's interval, in b's place
}

// Two cases whose stresses differ by 2 % but lives by 2.25× (a hand-typed life-test table over
// 8 and 12 N·m of a bending-dominated drive): n comes out near 40 with no interval to show it, and a
// warning says why; the same lives over a factor 2 of stress give n ≈ 1.2 without it.
TEST(LifeCardFit, TwoCasesOverANarrowStressRangeWarnThatNRestsOnIt) {
  auto two_cases = [](double low_MPa, double high_MPa) {
    std::vector<ObservedLife> cases(2);
    for (int k = 0; k < 2; ++k) {
      cases[k].name = "case" + std::to_string(k);
      cases[k].mode = Mode::radial_crack;
      cases[k].temperature_C = 60.0;
      cases[k].point_peaks_MPa = {{k == 0 ? low_MPa : high_MPa}};
      cases[k].observed_cycles = k == 0 ? 2.25e9 : 1e9;
    }
    return cases;
  };
  auto narrow_warning = [](const LifeCardFit& f) {
    for (const std::string& w : f.warnings)
      if (w.find("largest stress peaks span only a factor") != std::string::npos) return w;
    return std::string();
  };
  const LifeCardFit narrow = fit_life_card(two_cases(0.26, 0.265), default_card());
  EXPECT_NEAR(narrow.card.radial_crack.n, std::log(2.25) / std::log(0.265 / 0.26), 1e-6);
  EXPECT_NE(narrow_warning(narrow).find("(0.26 to 0.265 MPa)"), std::string::npos) << narrow_warning(narrow);
  const LifeCardFit wide = fit_life_card(two_cases(0.2, 0.4), default_card());
  EXPECT_NEAR(wide.card.radial_crack.n, std::log(2.25) / std::log(2.0), 1e-6);
  EXPECT_EQ(narrow_warning(wide), "");
  EXPECT_EQ(narrow_warning(fit_life_card(two_cases(0.26, 0.265), default_card(), {true, false})), "");  // n held
}

}  // namespace
}  // namespace fitlib::fatigue
