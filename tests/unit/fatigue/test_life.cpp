#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/life.hpp"

namespace fitlib::fatigue {
namespace {

// A point whose σ22 follows `values` at 1 s spacing (uniaxial longitudinal stress: σ_e = σ22
// for the radial crack when positive). Cushion points carry the values as σ12 (σ11 = 0).
PointHistory point(const std::string& name, Role role, const std::vector<double>& values,
                   double t0 = 0.0) {
  PointHistory p;
  p.name = name;
  p.role = role;
  for (std::size_t i = 0; i < values.size(); ++i) {
    StressSample s;
    s.t_s = t0 + static_cast<double>(i);
    (role == Role::bottom ? s.s22_MPa : s.s12_MPa) = values[i];
    p.samples.push_back(s);
  }
  return p;
}

LifeConditions at(double temperature_C) {
  LifeConditions c;
  c.temperature_C = temperature_C;
  c.cycles_per_hour = 3600.0;
  return c;
}

TEST(Life, OnePeakAtTheReferenceTemperatureIsTheInversePowerLaw) {
  const FatigueCard card = default_card();
  const LifeReport r = evaluate_life({point("a", Role::bottom, {0, 20, 0})}, card,
                                     at(card.reference_temperature_C));
  ASSERT_EQ(r.modes.size(), 1u);
  EXPECT_NEAR(r.life_cycles / std::pow(104.218 / 20.0, 4.423), 1.0, 1e-13);
  EXPECT_NEAR(r.life_h, r.life_cycles / 3600.0, 1e-9 * r.life_h);
  EXPECT_EQ(r.governing, "radial_crack");
}

// A life below 1000 cycles is a warning naming the mode, the life and the peak over σ0: one peak
// of σ0·1000^(−1/n)·(1 ± 1 %) sits just above and just below the threshold (N = (σ0/σ)ⁿ).
TEST(Life, ALifeBelowAThousandCyclesIsAWarningAndOneAboveIsNot) {
  const FatigueCard card = default_card();
  const double at_threshold = 104.218 * std::pow(kShortestReadableLife_cycles, -1.0 / 4.423);
  for (const double f : {1.01, 0.99}) {
    const LifeReport r = evaluate_life({point("a", Role::bottom, {0, f * at_threshold, 0})}, card,
                                       at(card.reference_temperature_C));
    const auto warnings = life_warnings(r);
    EXPECT_NEAR(r.modes[0].largest_peak_over_sigma0, f * at_threshold / 104.218, 1e-13);
    if (f > 1.0) {
      ASSERT_EQ(warnings.size(), 1u);
      EXPECT_LT(r.life_cycles, kShortestReadableLife_cycles);
      for (const char* part : {"radial_crack life", "below 1000", "x sigma0", "failure at once"})
        EXPECT_NE(warnings[0].find(part), std::string::npos) << part << " in " << warnings[0];
    } else {
      EXPECT_TRUE(warnings.empty()) << r.life_cycles;
    }
  }
}

// A life beyond 1e12 cycles is a runout warning naming the mode, the life and the peak over σ0
// (the light drive at zero torque gave separation 2.2e193 cycles with no word): one peak of
// σ0·1e12^(−1/n)·(1 ± 1 %) sits just below and just above the threshold; a mode with no peak at
// all (unbounded) is not one.
TEST(Life, ALifeBeyondATrillionCyclesIsARunoutWarningAndOneBelowIsNot) {
  const FatigueCard card = default_card();
  const double at_threshold = 104.218 * std::pow(kLongestReadableLife_cycles, -1.0 / 4.423);
  for (const double f : {0.99, 1.01}) {
    const LifeReport r = evaluate_life({point("a", Role::bottom, {0, f * at_threshold, 0})}, card,
                                       at(card.reference_temperature_C));
    const auto warnings = life_warnings(r);
    if (f < 1.0) {
      ASSERT_EQ(warnings.size(), 1u);
      EXPECT_GT(r.life_cycles, kLongestReadableLife_cycles);
      for (const char* part : {"radial_crack life", "beyond 1e+12", "x sigma0", "runout"})
        EXPECT_NE(warnings[0].find(part), std::string::npos) << part << " in " << warnings[0];
    } else {
      EXPECT_TRUE(warnings.empty()) << r.life_cycles;
    }
  }
  const LifeReport quiet = evaluate_life({point("a", Role::bottom, {0, 0, 0})}, card, at(card.reference_temperature_C));
  EXPECT_FALSE(std::isfinite(quiet.life_cycles));
  EXPECT_TRUE(life_warnings(quiet).empty());
}

TEST(Life, TemperatureFactorIsExactlyTwoToTheMinusBDeltaT) {
  const FatigueCard card = default_card();
  for (Role role : {Role::bottom, Role::cushion}) {
    const std::vector<PointHistory> pts = {point("p", role, {0, 3, 0.2, 1.5, 0})};
    const double n0 = evaluate_life(pts, card, at(card.reference_temperature_C)).life_cycles;
    for (double dT : {-30.0, 10.0, 47.5}) {
      const double n = evaluate_life(pts, card, at(card.reference_temperature_C + dT)).life_cycles;
      const double b = role == Role::bottom ? 0.02897 : 0.1466;
      EXPECT_NEAR(n / n0, std::exp2(-b * dT), 1e-13 * std::exp2(-b * dT));
    }
  }
}

TEST(Life, MEqualPeaksDivideTheLifeByM) {
  const FatigueCard card = default_card();
  const double one =
      evaluate_life({point("p", Role::cushion, {0, 1.2, 0})}, card, at(95.0)).life_cycles;
  for (int m : {2, 3, 7}) {
    std::vector<double> v;
    for (int k = 0; k < m; ++k) v.insert(v.end(), {0.0, 1.2});
    v.push_back(0.0);
    const LifeReport r = evaluate_life({point("p", Role::cushion, v)}, card, at(95.0));
    EXPECT_EQ(r.modes[0].peaks.size(), static_cast<std::size_t>(m));
    EXPECT_NEAR(r.life_cycles * m / one, 1.0, 1e-13);
  }
}

TEST(Life, OnePeakOfOneSampleThatCarriesTheSumIsFlaggedAndAResolvedOneIsNot) {
  const FatigueCard card = default_card();  // mode 2: n = 11.69, half-term level 2^(-1/n) = 0.9425
  // The peel transient as one sample at 0.63 MPa over a 0.35 MPa plateau (Σ 99.9 % that peak).
  const LifeReport spike = evaluate_life({point("p", Role::cushion, {0, 0.35, 0.35, 0.63, 0.36, 0.35, 0})}, card, at(95.0));
  EXPECT_EQ(spike.modes[0].dominant_peak_samples, 1);
  EXPECT_GT(spike.modes[0].dominant_peak_share, 0.99);
  EXPECT_TRUE(peak_under_resolved(spike.modes[0]));
  // The same top carried by three samples within its half-term band (0.60 ≥ 0.9425 · 0.63 = 0.594).
  const LifeReport resolved =
      evaluate_life({point("p", Role::cushion, {0, 0.35, 0.60, 0.63, 0.61, 0.35, 0})}, card, at(95.0));
  EXPECT_EQ(resolved.modes[0].dominant_peak_samples, 3);
  EXPECT_FALSE(peak_under_resolved(resolved.modes[0]));
  // Two equal single-sample peaks: each carries half the sum, so no one peak dominates.
  const LifeReport two = evaluate_life({point("p", Role::cushion, {0, 0.63, 0.1, 0.63, 0})}, card, at(95.0));
  EXPECT_NEAR(two.modes[0].dominant_peak_share, 0.5, 1e-12);
  EXPECT_FALSE(peak_under_resolved(two.modes[0]));
}

TEST(Life, DesignPointIsTheLargestSumAndGoverningModeTheShortestLife) {
  FatigueCard card = default_card();
  // Point "one" has a single 30 MPa peak, point "many" four 20 MPa peaks: with n = 4.423,
  // 30ⁿ > 4·20ⁿ (1.5ⁿ ≈ 6.0 > 4), so "one" is the design point; with
  // n = 2, 4·20² = 1600 > 900 and "many" is.
  const std::vector<PointHistory> pts = {point("one", Role::bottom, {0, 30, 0}),
                                         point("many", Role::bottom, {0, 20, 0, 20, 0, 20, 0, 20, 0}),
                                         point("cushion", Role::cushion, {0, 1.0, 0})};
  const double T = card.reference_temperature_C;
  LifeReport r = evaluate_life(pts, card, at(T));
  EXPECT_EQ(r.modes[0].design_point, "one");
  card.radial_crack.n = 2.0;
  r = evaluate_life(pts, card, at(T));
  EXPECT_EQ(r.modes[0].design_point, "many");
  EXPECT_NEAR(r.modes[0].sum_terms, 4.0 * std::pow(20.0 / 104.218, 2.0), 1e-14);
  // Mode 2 with 1 MPa: (4.21028)^11.69 ≈ 2e7 cycles; mode 1 with n = 2 ≈ 6.8: separation lives
  // longer, the radial crack governs.
  ASSERT_EQ(r.modes.size(), 2u);
  EXPECT_EQ(r.governing, "radial_crack");
  EXPECT_DOUBLE_EQ(r.life_cycles, std::min(r.modes[0].life_cycles, r.modes[1].life_cycles));
}

TEST(Life, MinersRuleOverThePulleysOfOneCycle) {
  const FatigueCard card = default_card();
  // One cycle of 8 s: a small pulley (peaks 25 and 18) then a large one (peak 12).
  const std::vector<double> small = {0, 25, 0, 18}, large = {0, 12, 0, 0};
  std::vector<double> cycle = small;
  cycle.insert(cycle.end(), large.begin(), large.end());
  LifeConditions c = at(90.0);
  c.pulleys = {{"small", 0.0, 4.0}, {"large", 4.0, 8.0}};
  const LifeReport r = evaluate_life({point("p", Role::bottom, cycle)}, card, c);
  ASSERT_EQ(r.modes[0].shares.size(), 2u);
  // Each pulley alone (its part repeated as the whole cycle), then 1/N = Σ 1/N_j.
  const double n_small =
      evaluate_life({point("p", Role::bottom, small)}, card, at(90.0)).life_cycles;
  const double n_large =
      evaluate_life({point("p", Role::bottom, large)}, card, at(90.0)).life_cycles;
  EXPECT_NEAR(r.modes[0].shares[0].damage_per_cycle * n_small, 1.0, 1e-13);
  EXPECT_NEAR(r.modes[0].shares[1].damage_per_cycle * n_large, 1.0, 1e-13);
  EXPECT_NEAR(r.life_cycles * (1.0 / n_small + 1.0 / n_large), 1.0, 1e-13);
}

TEST(Life, OnlyTheLastCycleCounts) {
  const FatigueCard card = default_card();
  // Cycle 1 has a large transient peak; cycle 2 (t = 4 … 7) is the steady one.
  PointHistory p = point("p", Role::bottom, {0, 50, 0, 0, 0, 10, 0, 0});
  LifeConditions c = at(80.0);
  c.cycle_time_s = 4.0;
  const LifeReport r = evaluate_life({p}, card, c);
  ASSERT_EQ(r.modes[0].peaks.size(), 1u);
  EXPECT_DOUBLE_EQ(r.modes[0].peaks[0].stress_MPa, 10.0);
  EXPECT_DOUBLE_EQ(r.modes[0].peaks[0].t_s, 5.0);
}

TEST(Life, CordBreakByGerbert) {
  const CordBreakLaw law{8.0, 0.02, 400.0, 5.0, 0.1};
  // Force 500 … 1500 N on 5 mm²: σ_m = 200 = σ_U/2, σ_a = 100 → σ_A = 2σ_a (3.6).
  const CordBreakLife k = cord_break_life({500, 1500, 1000}, law, 90.0, 80.0, 1000.0);
  EXPECT_DOUBLE_EQ(k.mean_MPa, 200.0);
  EXPECT_DOUBLE_EQ(k.equivalent_amplitude_MPa, 200.0);
  EXPECT_NEAR(k.life_cycles, std::pow(10.0, 8.0 - 4.0) * 0.5, 1e-9);  // ΔT = +10 halves (3.7)
  EXPECT_NEAR(cord_break_life({500, 1500}, law, 70.0, 80.0, 0).life_cycles, 2e4, 1e-9);
  EXPECT_THROW(cord_break_life({2000, 2100}, law, 80.0, 80.0, 0), core::InputError);
  // In the report it competes with the crack modes.
  FatigueCard card = default_card();
  card.cord_break = law;
  LifeConditions c = at(90.0);
  c.cord_force_N = {500, 1500};
  const LifeReport r = evaluate_life({point("p", Role::bottom, {0, 1.0, 0})}, card, c);
  EXPECT_EQ(r.governing, "cord_break");
  EXPECT_DOUBLE_EQ(r.life_cycles, 5e3);
}

TEST(Life, NoPeakMeansUnboundedAndJsonWritesNull) {
  const LifeReport r =
      evaluate_life({point("p", Role::cushion, {0, 0, 0})}, default_card(), at(80.0));
  EXPECT_EQ(r.governing, "none");
  EXPECT_FALSE(std::isfinite(r.life_cycles));
  const nlohmann::json j = life_to_json(r);
  EXPECT_TRUE(j["life_cycles"].is_null());
  EXPECT_TRUE(j["unbounded"].get<bool>());
  EXPECT_EQ(j.dump().find("inf"), std::string::npos);
  EXPECT_EQ(j.dump().find("nan"), std::string::npos);
}

TEST(Life, TableNamesModesDesignPointsAndTheGoverningMode) {
  FatigueCard card = default_card();
  const LifeReport r = evaluate_life({point("gap", Role::bottom, {0, 20, 0}),
                                      point("cushion", Role::cushion, {0, 0, 0})},
                                     card, at(card.reference_temperature_C));
  const std::string t = life_table(r);
  char expected[64];
  std::snprintf(expected, sizeof expected, "%.4g cycles", std::pow(104.218 / 20.0, 4.423));
  EXPECT_NE(t.find(std::string("radial_crack  ") + expected), std::string::npos) << t;
  EXPECT_NE(t.find("design point gap"), std::string::npos) << t;
  EXPECT_NE(t.find("separation    unbounded"), std::string::npos) << t;
  EXPECT_NE(t.find("governing: radial_crack"), std::string::npos) << t;
}

TEST(Life, BadHistoriesAreRefused) {
  PointHistory p = point("p", Role::bottom, {0, 1, 0});
  p.samples[1].s12_MPa = std::nan("");
  EXPECT_THROW(evaluate_life({p}, default_card(), at(80.0)), core::NumericalError);
  PointHistory q = point("q", Role::bottom, {0, 1, 0});
  q.samples[2].t_s = 0.5;
  try {
    evaluate_life({q}, default_card(), at(80.0));
    FAIL();
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), "points.q");
  }
  EXPECT_THROW(evaluate_life({point("e", Role::bottom, {})}, default_card(), at(80.0)),
               core::InputError);
}

// The reference of 2^(−bΔT) (docs/decisions.md "Fatigue: the reference temperature of 2^(-b dT) read
// against the thesis"): ΔT is measured from the card's reference_temperature_C, not from 0 °C (the
// Celsius zero of T in (6.24)) nor room temperature; Report I's card keeps 80 °C, inside the
// 60–140 °C over which Report III states the halving per 10 °C (L2949). Moving the reference by
// 60 °C is the lever the decision pins: 2^(60 b), 445x on separation, 3.34x on the radial crack.
TEST(Life, TheReferenceOfDeltaTIsTheCardsEightyDegreesInsideTheLawsStatedRange) {
  const FatigueCard card = default_card();
  EXPECT_EQ(card.reference_temperature_C, 80.0);
  EXPECT_GE(card.reference_temperature_C, 60.0);
  EXPECT_LE(card.reference_temperature_C, 140.0);
  FatigueCard room = card;
  room.reference_temperature_C = 20.0;
  for (Role role : {Role::bottom, Role::cushion}) {
    const std::vector<PointHistory> pts = {point("p", role, {0, 3, 0.2, 1.5, 0})};
    const double b = role == Role::bottom ? 0.02897 : 0.1466;
    const double at80 = evaluate_life(pts, card, at(80.0)).life_cycles;
    EXPECT_NEAR(evaluate_life(pts, card, at(80.0)).modes[0].temperature_factor, 1.0, 0.0);
    EXPECT_NEAR(evaluate_life(pts, room, at(80.0)).life_cycles / at80, std::exp2(-60.0 * b), 1e-12);
  }
  EXPECT_NEAR(std::exp2(60.0 * 0.1466), 444.5, 0.1);
}

// A life whose stresses came from a card read beyond its tests (ModeLife::beyond_tests, set by the
// scene) prints kDigitsBeyondTests significant digits and its clause, and the JSON flags it.
TEST(Life, ALifeReadBeyondTheTestsIsPrintedWithTwoDigitsAndFlagged) {
  const FatigueCard card = default_card();
  LifeReport r = evaluate_life({point("a", Role::bottom, {0, 2.345678, 0})}, card, at(80.0));
  EXPECT_NE(life_table(r).find(" cycles ("), std::string::npos);
  char four[32], two[32];
  std::snprintf(four, sizeof four, "%.4g cycles", r.life_cycles);
  std::snprintf(two, sizeof two, "%.2g cycles", r.life_cycles);
  EXPECT_NE(life_table(r).find(four), std::string::npos) << life_table(r);
  EXPECT_FALSE(life_to_json(r)["modes"][0].contains("extrapolated"));
  r.modes[0].beyond_tests = "bottom read at 2.1x its largest tested amplitude (0.095 against 0.045)";
  r.modes[0].significant_digits = kDigitsBeyondTests;
  const std::string table = life_table(r);
  EXPECT_EQ(table.find(four), std::string::npos) << table;
  EXPECT_NE(table.find(two), std::string::npos) << table;
  EXPECT_NE(table.find("governing: radial_crack, " + std::string(two)), std::string::npos) << table;
  EXPECT_NE(table.find("beyond the tests: bottom read at 2.1x"), std::string::npos) << table;
  const auto j = life_to_json(r);
  EXPECT_TRUE(j["modes"][0]["extrapolated"].get<bool>());
  EXPECT_EQ(j["modes"][0]["life_cycles"].get<double>(), r.life_cycles);  // the JSON keeps every digit
}

}  // namespace
}  // namespace fitlib::fatigue
