// Report II §7.2 cases at a material point (material 1): the loops are well formed, damage grows
// over the first cycles and softens the loop, the ramp relaxes while held.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fitlib/core/error.hpp"
#include "fitlib/model/fritzson_cases.hpp"
#include "materials.hpp"

namespace {

using namespace fitlib::model;
using namespace fitlib::model::fritzson;
// fritzson's own point and driver (model:: has the generic ones of the same names)
using fitlib::model::fritzson::DriveResult;
using fitlib::model::fritzson::MaterialPoint;

// Peak-to-peak stress over cycle `k` (0-based) of a cyclic case.
double peak_to_peak(const CaseLoops& l, int k, int steps) {
  const auto begin = l.stress_MPa.begin() + k * steps, end = begin + steps + 1;
  return *std::max_element(begin, end) - *std::min_element(begin, end);
}

TEST(FritzsonCases, FourCyclicCasesSoftenWhileDamageSettles) {
  const MaterialPoint point(fritzson_test::material1_parameters(), true, 23.0, Scheme::exponential);
  const int steps = 100;
  for (const char* id : {"7.1", "7.2", "7.3", "7.4"}) {
    const ThesisCase& c = thesis_case(id);
    const CaseLoops l = run_thesis_case(point, c, steps);
    ASSERT_EQ(l.time_s.size(), size_t(10 * steps + 1)) << id;
    EXPECT_DOUBLE_EQ(l.stress_MPa.front(), 0.0) << id;  // starts unstrained
    for (double s : l.stress_MPa) ASSERT_TRUE(std::isfinite(s)) << id;
    // Damage drivers never decrease; most of the growth happens in the first cycles.
    const int part = c.orientation == "33" ? 1 : (c.orientation == "23" ? 2 : 0);
    for (size_t k = 1; k < l.driver_amplitude.size(); ++k)
      EXPECT_GE(l.driver_amplitude[k][part], l.driver_amplitude[k - 1][part]) << id;
    const double after1 = l.driver_amplitude[steps][part], after10 = l.driver_amplitude.back()[part];
    EXPECT_GT(after1, 0.5 * after10) << id;
    EXPECT_LT(peak_to_peak(l, 9, steps), peak_to_peak(l, 1, steps)) << id;
    // Compressive cycles (mean −1 × amplitude): the stress is mostly negative in uniaxial cases.
    if (c.mode == TestMode::uniaxial) {
      EXPECT_LT(*std::min_element(l.stress_MPa.begin(), l.stress_MPa.end()), 0.0) << id;
      EXPECT_NEAR(l.strain[steps / 2], std::log1p(-2 * c.displacement_amplitude), 1e-12) << id;
    }
  }
  const std::string csv = case_loops_csv(thesis_case("7.3"), run_thesis_case(point, thesis_case("7.3"), 16));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2 + 161);
}

TEST(FritzsonCases, InterruptedRampRelaxesDuringTheHold) {
  const MaterialPoint point(fritzson_test::material1_parameters(), true, 23.0, Scheme::exponential);
  const ThesisCase& c = thesis_case("7.5");
  const int rise_steps = 200;
  const CaseLoops l = run_thesis_case(point, c, rise_steps);
  EXPECT_NEAR(l.strain[rise_steps], std::log(1.1), 1e-12);
  EXPECT_NEAR(l.time_s[rise_steps], std::log(1.1) / 5.0, 1e-12);
  const double peak = l.stress_MPa[rise_steps];
  EXPECT_GT(peak, 0.0);
  for (size_t k = rise_steps + 1; k < l.stress_MPa.size(); ++k)
    EXPECT_LE(l.stress_MPa[k], l.stress_MPa[k - 1] + 1e-12);
  EXPECT_LT(l.stress_MPa.back(), 0.8 * peak);
  EXPECT_THROW(thesis_case("7.6"), fitlib::core::UsageError);
}

// Lagged damage (PointOptions::DamageUpdate::lagged: the step's stress uses the converged e^a_n)
// against the thesis's implicit update on the four cyclic cases, same steps: the difference is the
// lag's time-integration error, O(Δt) — halving the step halves it (ratio ≈ 2), and it vanishes
// once damage has settled (the last cycle differs far less than the first).
double largest_difference(const CaseLoops& a, const CaseLoops& b, std::size_t from, std::size_t to) {
  double d = 0.0, scale = 0.0;
  for (std::size_t k = from; k < to; ++k)
    d = std::max(d, std::abs(a.stress_MPa[k] - b.stress_MPa[k])), scale = std::max(scale, std::abs(b.stress_MPa[k]));
  return d / scale;
}

TEST(FritzsonCases, LaggedDamageConvergesToTheImplicitUpdateAtFirstOrder) {
  const std::vector<double> p = fritzson_test::material1_parameters();
  const MaterialPoint implicit(p, true, 23.0, Scheme::exponential, DamageUpdate::implicit);
  const MaterialPoint lagged(p, true, 23.0, Scheme::exponential, DamageUpdate::lagged);
  for (const char* id : {"7.1", "7.2", "7.3", "7.4"}) {
    std::vector<double> first_cycle, last_cycle;
    for (int steps : {100, 200, 400}) {
      const CaseLoops a = run_thesis_case(lagged, thesis_case(id), steps);
      const CaseLoops b = run_thesis_case(implicit, thesis_case(id), steps);
      first_cycle.push_back(largest_difference(a, b, 0, steps + 1));
      last_cycle.push_back(largest_difference(a, b, 9 * steps, a.stress_MPa.size()));
    }
    std::printf("case %s: lagged − implicit, first cycle %.3g / %.3g / %.3g of the peak at 100 / 200 / 400 "
                "steps per cycle; last cycle %.3g\n", id, first_cycle[0], first_cycle[1], first_cycle[2],
                last_cycle[0]);
    EXPECT_NEAR(first_cycle[0] / first_cycle[1], 2.0, 0.3) << id;
    EXPECT_NEAR(first_cycle[1] / first_cycle[2], 2.0, 0.3) << id;
    EXPECT_LT(first_cycle[0], 0.05) << id;
    EXPECT_LT(last_cycle[0], 0.2 * first_cycle[0]) << id;
  }
}

}  // namespace
