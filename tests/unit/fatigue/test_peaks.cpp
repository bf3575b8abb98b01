#include <gtest/gtest.h>

#include <vector>

#include "fitlib/fatigue/peaks.hpp"

namespace fitlib::fatigue {
namespace {

std::vector<double> values_of(const std::vector<Extremum>& e) {
  std::vector<double> v;
  for (const Extremum& x : e) v.push_back(x.value);
  return v;
}

// Extrema of {0, 10, 1, 2, 0.5, 6, 3, 4, 0} on a periodic cycle (the two zeros at the ends are
// one plateau): max 10, min 1, max 2, min 0.5, max 6, min 3, max 4, min 0. Step 2 (25 % of 10 =
// 2.5) drops max 2 and min 3; step 3 keeps 6 of the maxima 6, 4; step 4 keeps 0.5 of 1, 0.5.
TEST(Peaks, FourStepsOnAConstructedCycle) {
  const std::vector<double> v = {0, 10, 1, 2, 0.5, 6, 3, 4, 0};
  EXPECT_EQ(local_extrema(v, true).size(), 8u);
  const std::vector<Extremum> e = significant_extrema(v);
  EXPECT_EQ(values_of(e), (std::vector<double>{10, 0.5, 6, 0}));
  EXPECT_EQ(e[0].index, 1u);
  EXPECT_EQ(e[3].index, 8u);  // the wrapped plateau is placed at its first sample
  EXPECT_EQ(values_of(significant_peaks(v)), (std::vector<double>{10, 6}));
}

TEST(Peaks, ThresholdIsAShareOfTheLargestMaximum) {
  // Bumps of 2.4 and 2.6 between deep minima: 25 % of 10 drops the first only.
  const std::vector<double> v = {0, 10, 0, 2.4, 0, 2.6, 0};
  EXPECT_EQ(values_of(significant_peaks(v)), (std::vector<double>{10, 2.6}));
  PeakOptions half;
  half.threshold = 0.5;
  EXPECT_EQ(values_of(significant_peaks(v, half)), (std::vector<double>{10}));
}

TEST(Peaks, ShallowMinimaDoNotSeparateMaxima) {
  // The minimum 5 between 8 and 9 lies above 25 % of 9: the two maxima are one peak, 9.
  const std::vector<double> v = {0, 8, 5, 9, 0, 4, 0};
  EXPECT_EQ(values_of(significant_peaks(v)), (std::vector<double>{9, 4}));
}

TEST(Peaks, RunAroundTheCycleEnd) {
  // Maxima 7 (end) and 9 (start) are neighbours across the cycle's end with no significant
  // minimum between them: one peak.
  const std::vector<double> v = {8, 9, 6, 1, 6, 7, 6.5};
  EXPECT_EQ(values_of(significant_peaks(v)), (std::vector<double>{9}));
  // Not periodic: the end samples are never extrema; 9 and 7 are separated by the minimum 1.
  PeakOptions open;
  open.periodic = false;
  EXPECT_EQ(values_of(significant_peaks(v, open)), (std::vector<double>{9, 7}));
}

TEST(Peaks, PlateausCountOnceAndConstantsHaveNone) {
  const std::vector<double> v = {0, 5, 5, 5, 0, 3, 3, 0};
  const std::vector<Extremum> p = significant_peaks(v);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].index, 1u);
  EXPECT_TRUE(significant_peaks(std::vector<double>(10, 2.0)).empty());
  EXPECT_TRUE(significant_peaks({}).empty());
}

TEST(Peaks, NoSignificantMinimumLeavesTheLargestMaximum) {
  // Always above 25 % of the largest maximum: every minimum is dropped, one peak remains.
  const std::vector<double> v = {5, 6, 5.5, 8, 5, 7, 5};
  EXPECT_EQ(values_of(significant_peaks(v)), (std::vector<double>{8}));
}

}  // namespace
}  // namespace fitlib::fatigue
