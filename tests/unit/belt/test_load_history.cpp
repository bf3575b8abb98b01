// belt::LoadHistory: linear between samples, the value after a jump, periodic in s and t.
#include <gtest/gtest.h>

#include "fitlib/belt/load_history.hpp"
#include "fitlib/core/error.hpp"

namespace {

using namespace fitlib::belt;

LoadCycle synthetic_cycle() {
  LoadCycle c;
  c.cycle_length_mm = 40.0;
  c.cycle_time_s = 20.0;  // V = 2 mm/s
  const double s[] = {0.0, 10.0, 10.0, 30.0}, F[] = {100.0, 200.0, 400.0, 300.0};
  for (int i = 0; i < 4; ++i) {
    LoadSample q;
    q.s_mm = s[i];
    q.t_s = s[i] / 2.0;
    q.F_N = F[i];
    q.p_MPa = 0.1 * i;
    q.K_1_mm = 0.01 * i;
    q.gamma_rad = 0.2 * i;
    c.samples.push_back(q);
  }
  return c;
}

TEST(LoadHistory, InterpolatesLinearlyAndTakesTheValueAfterAJump) {
  BeltSection belt;
  belt.c_N = 1000.0;
  const LoadHistory h(synthetic_cycle(), belt, 80.0);
  EXPECT_DOUBLE_EQ(h.at_position(5.0).F_N, 150.0);
  EXPECT_DOUBLE_EQ(h.at_position(5.0).strain, 0.15);
  EXPECT_DOUBLE_EQ(h.at_position(10.0).F_N, 400.0);
  EXPECT_DOUBLE_EQ(h.at_position(20.0).F_N, 350.0);
  EXPECT_DOUBLE_EQ(h.at_position(20.0).gamma_rad, 0.5);
  EXPECT_DOUBLE_EQ(h.at_position(20.0).temperature_C, 80.0);
}

TEST(LoadHistory, IsPeriodicOverTheBeltLengthAndTheCycleTime) {
  BeltSection belt;
  const LoadHistory h(synthetic_cycle(), belt, 80.0);
  // Between the last sample (30 mm, 300 N) and the first one a length later (40 mm, 100 N).
  EXPECT_DOUBLE_EQ(h.at_position(35.0).F_N, 200.0);
  EXPECT_DOUBLE_EQ(h.at_position(35.0 + 3 * 40.0).F_N, 200.0);
  EXPECT_DOUBLE_EQ(h.at_position(-5.0).F_N, 200.0);
  EXPECT_DOUBLE_EQ(h.at_time(17.5).F_N, 200.0);  // s = V t = 35 mm
  EXPECT_DOUBLE_EQ(h.at_time(17.5 + 20.0).t_s, 17.5);
  LoadCycle still = synthetic_cycle();
  still.cycle_time_s = 0.0;
  EXPECT_THROW(LoadHistory(still, belt, 20.0).at_time(1.0), fitlib::core::UsageError);
  EXPECT_THROW(LoadHistory(LoadCycle{}, belt, 20.0), fitlib::core::InputError);
}

// The history seen from another path origin: at every position (across the wrap and the jump at
// 10 mm) the original's a shift further on, and the time counted from where the belt passes it.
TEST(LoadHistory, ShiftedReadsTheOriginalFromTheNewOrigin) {
  BeltSection belt;
  belt.c_N = 1000.0;
  const LoadHistory h(synthetic_cycle(), belt, 80.0);
  for (double shift : {0.0, 7.5, 10.0, 25.0, 39.0}) {
    const LoadHistory g = h.shifted(shift);
    EXPECT_EQ(g.samples().size(), h.samples().size());
    for (double x = -40.0; x <= 80.0; x += 0.37) {
      EXPECT_NEAR(g.at_position(x).F_N, h.at_position(x + shift).F_N, 1e-9) << shift << " " << x;
      EXPECT_NEAR(g.at_position(x).p_MPa, h.at_position(x + shift).p_MPa, 1e-12) << shift << " " << x;
    }
    EXPECT_NEAR(g.at_time(0.0).F_N, h.at_position(shift).F_N, 1e-9) << shift;
  }
}

}  // namespace
