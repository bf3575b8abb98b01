// The material-point work cap is by cost (fitlib/model/work_caps.hpp, docs/reliability.md §4): the
// same number of steps runs for a cheap point and is refused for a dear one, before any work.
#include <gtest/gtest.h>

#include <string>

#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/model.hpp"
#include "fitlib/model/work_caps.hpp"

namespace fitlib::model {
namespace {

std::string refusal(const PointWork& w, const std::string& key) {
  try {
    check_point_work(w, "a point", key);
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), key);
    return e.what();
  }
  return "";
}

TEST(PointWorkCap, TheEstimateIsTheCostModelsSum) {
  // 1e5 steps of a 1000-value state, strain-controlled: 1e5 (2.25 + 2.55 + 4.3) us = 0.91 s.
  EXPECT_NEAR(point_work(1000, 1e5, false).seconds, 0.91, 1e-12);
  // Stress-controlled: two updates a step, 1e5 (2.25 + 2 (2.55 + 4.3)) us = 1.595 s.
  EXPECT_NEAR(point_work(1000, 1e5, true).seconds, 1.595, 1e-12);
  EXPECT_EQ(point_work(0, 10, TestMode::uniaxial).updates_per_step, 2.0);
  EXPECT_EQ(point_work(0, 10, TestMode::shear).updates_per_step, 1.0);
  EXPECT_EQ(point_work(0, 10, TestMode::bulk).updates_per_step, 1.0);
}

TEST(PointWorkCap, SameStepsRunForACheapPointAndAreRefusedForADearOne) {
  const double steps = 5e5;
  PointOptions o;
  o.bulk_modulus_MPa = 2000.0;
  const auto cheap = make_material_point(*make_model("prony", {{"terms", 1}}), {1.0, 1.0, 0.1}, o);
  const auto zener = make_model("fractional-zener", nlohmann::json::object());
  const auto dear = make_material_point(*zener, zener->default_parameters(), o);
  EXPECT_EQ(refusal(point_work(cheap->state_size(), steps, TestMode::uniaxial), "--cycles"), "");
  const std::string why = refusal(point_work(dear->state_size(), steps, TestMode::uniaxial), "--cycles");
  EXPECT_NE(why.find("key '--cycles'"), std::string::npos) << why;
  EXPECT_NE(why.find(std::to_string(dear->state_size()) + " state values"), std::string::npos) << why;
  EXPECT_NE(why.find("work cap of 10 s estimated"), std::string::npos) << why;
  // The shear test of the dear point (no Newton correction) is within the cap.
  EXPECT_EQ(refusal(point_work(dear->state_size(), steps, TestMode::shear), "--cycles"), "");
}

TEST(PointWorkCap, RowsAreCappedWhateverTheirCost) {
  EXPECT_EQ(refusal(point_work(0, kMaxPointSteps, false), "len(time_s)"), "");
  const std::string why = refusal(point_work(0, 2 * kMaxPointSteps, false), "len(time_s)");
  EXPECT_NE(why.find("2e+06 time steps"), std::string::npos) << why;
  EXPECT_NE(why.find("140 MB"), std::string::npos) << why;
}

}  // namespace
}  // namespace fitlib::model
