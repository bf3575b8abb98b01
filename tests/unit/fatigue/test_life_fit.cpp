#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/fatigue/life_fit.hpp"

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
  const LifeLaw truth{4.21028, 11.69, 0.1466};
  auto cases = synthetic(Mode::separation, truth, 12, 0.0, 5);
  // Cases of the other mode are ignored by this mode's fit.
  auto other = synthetic(Mode::radial_crack, LifeLaw{104.218, 4.423, 0.02897}, 5, 0.0, 6);
  cases.insert(cases.end(), other.begin(), other.end());
  LifeFitOptions o;
  o.start = LifeLaw{8.0, 6.0, 0.05};
  const LifeFitResult r = fit_life_law(cases, Mode::separation, o);
  EXPECT_EQ(r.cases, 12);
  EXPECT_NEAR(r.law.sigma0_MPa / truth.sigma0_MPa, 1.0, 1e-7);
  EXPECT_NEAR(r.law.n / truth.n, 1.0, 1e-7);
  EXPECT_NEAR(r.law.b_per_C / truth.b_per_C, 1.0, 1e-7);
  EXPECT_LT(r.rms_log10_error, 1e-8);
}

TEST(LifeFit, IntervalsCoverTheTruthWithScatter) {
  const LifeLaw truth{104.218, 4.423, 0.02897};
  const auto cases = synthetic(Mode::radial_crack, truth, 30, 0.15, 17);
  LifeFitOptions o;
  o.start = LifeLaw{50.0, 3.0, 0.0};
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
  const LifeLaw truth{4.21028, 11.69, 0.1466};
  const auto cases = synthetic(Mode::separation, truth, 8, 0.0, 9, false);
  LifeFitOptions o;
  o.start = LifeLaw{6.0, 9.0, 0.1466};
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
  try {
    parse_observed_lives(text, "lives.csv");
    FAIL() << text;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.file(), "lives.csv");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.column(), column) << e.what();
    if (!key.empty()) {
      EXPECT_EQ(e.key(), key) << e.what();
    }
  }
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
}

}  // namespace
}  // namespace fitlib::fatigue
