#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/beam_section.hpp"
#include "fitlib/fatigue/stress_csv.hpp"
#include "csv_error.hpp"

namespace fitlib::fatigue {
namespace {

TEST(StressCsv, RoundTripGivesTheSameLife) {
  // A beam-level history (three samples, bent in the middle) written and read back.
  belt::DriveCase d;
  d.belt_speed_mm_s = 5000.0;
  belt::LoadCycle c;
  for (int i = 0; i < 3; ++i) {
    belt::LoadSample s;
    s.s_mm = 7.0 * i;
    s.F_N = 300.0 + 10.0 * i;
    s.K_1_mm = i == 1 ? 0.02 : 0.0;
    s.p_MPa = i == 1 ? 1.3 : 0.0;
    s.gamma_rad = 2.0;
    s.friction_used = 0.4;
    c.samples.push_back(s);
  }
  const auto points = beam_stress_histories(c, d, BeamSection{});
  const std::string text = stress_histories_csv(points);
  const auto back = parse_stress_histories(text, "s.csv");
  ASSERT_EQ(back.size(), points.size());
  EXPECT_EQ(stress_histories_csv(back), text);
  LifeConditions cond;
  EXPECT_EQ(life_to_json(evaluate_life(back, default_card(), cond)),
            life_to_json(evaluate_life(points, default_card(), cond)));
}

TEST(StressCsv, InterleavedPointsAndErrorsWithLineAndColumn) {
  const std::string head = "point,role,x_mm,y_mm,t_s,s11_MPa,s22_MPa,s12_MPa\n";
  const auto p = parse_stress_histories(
      head + "a,bottom,0,-4.1,0,0,1,0\nb,cushion,0,-0.25,0,0,0,0.5\na,bottom,0,-4.1,1,0,2,0\n", "s.csv");
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].samples.size(), 2u);
  EXPECT_EQ(p[1].role, Role::cushion);
  auto expect_error = [](const std::string& text, int line, int column) {
    expect_csv_error(parse_stress_histories, text, line, column);
  };
  expect_error(head + "a,cog,0,0,0,0,0,0\n", 2, 2);
  expect_error(head + "a,bottom,0,0,0,0,nan,0\n", 2, 7);
  expect_error(head + "a,bottom,0,0,1,0,0,0\na,bottom,0,0,1,0,0,0\n", 3, 5);
  expect_error(head + "a,bottom,0,0,0,0,0,0\na,cushion,0,0,1,0,0,0\n", 3, 1);
  expect_error("point,role,x_mm,y_mm,t,s11_MPa,s22_MPa,s12_MPa\n", 1, 5);
  expect_error(head + "a,bottom,0,0,0,0,0\n", 2, 8);
  expect_error(head, 1, 0);
  // The strains are optional columns, each field may be empty (the beam level has none).
  const std::string with = "point,role,x_mm,y_mm,t_s,s11_MPa,s22_MPa,s12_MPa,e11,e22,e12\n";
  const auto q = parse_stress_histories(with + "a,bottom,0,-4.1,0,0,1,0,0.01,-0.02,0.005\nb,cushion,0,0,0,0,0,0,,,\n", "s.csv");
  EXPECT_EQ(q[0].samples[0].e22, -0.02);
  EXPECT_TRUE(std::isnan(q[1].samples[0].e11));
  EXPECT_EQ(stress_histories_csv(q), with + "a,bottom,0,-4.1,0,0,1,0,0.01,-0.02,0.005\nb,cushion,0,0,0,0,0,0,,,\n");
  expect_error(with + "a,bottom,0,0,0,0,0,0,0,0\n", 2, 11);
  expect_error(with + "a,bottom,0,0,0,0,0,0,x,0,0\n", 2, 9);
}

}  // namespace
}  // namespace fitlib::fatigue
