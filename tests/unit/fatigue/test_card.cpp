#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "fitlib/core/error.hpp"
#include "fitlib/fatigue/card.hpp"

namespace fitlib::fatigue {
namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string path = fitlib_test::temp_path(name);
  std::ofstream(path) << text;
  return path;
}

TEST(FatigueCard, DefaultHoldsThePrintedConstants) {
  const FatigueCard c = default_card();
  EXPECT_EQ(c.radial_crack.sigma0_MPa, 104.218);
  EXPECT_EQ(c.radial_crack.n, 4.423);
  EXPECT_EQ(c.radial_crack.b_per_C, 0.02897);
  EXPECT_EQ(c.separation.sigma0_MPa, 4.21028);
  EXPECT_EQ(c.separation.n, 11.69);
  EXPECT_EQ(c.separation.b_per_C, 0.1466);
  EXPECT_EQ(c.reference_temperature_C, 80.0);
  EXPECT_EQ(c.crack_sweep_deg, 25.0);
  EXPECT_FALSE(c.cord_break);
}

TEST(FatigueCard, BundledCardIsTheDefault) {
  const FatigueCard c =
      load_card(std::string(FITLIB_SOURCE_DIR) + "/datasets/cards/fatigue-fritzson-1988.json");
  EXPECT_EQ(card_to_json(c), card_to_json(default_card()));
}

// The level of the stresses each mode's constants were fitted to: Report I's are the complete
// model's; a card may leave it unstated; the warning names the modes and levels that differ.
TEST(FatigueCard, EachModeStatesTheStressLevelItsConstantsWereFittedTo) {
  FatigueCard c = default_card();
  EXPECT_EQ(c.radial_crack.stress_fidelity, "complete");
  EXPECT_EQ(c.separation.stress_fidelity, "complete");
  EXPECT_EQ(stress_fidelity_warning(c, "complete"), "");
  EXPECT_EQ(stress_fidelity_warning(c, "beam").rfind("the fatigue card's radial_crack and separation constants "
                                                     "were fitted to complete-level stresses, and this run's "
                                                     "stresses are the beam level's", 0), 0u);
  c.radial_crack.stress_fidelity = "elastic";
  c.separation.stress_fidelity = "";
  EXPECT_EQ(stress_fidelity_warning(c, "elastic"), "");
  EXPECT_EQ(stress_fidelity_warning(c, "beam").rfind("the fatigue card's radial_crack constants were fitted to "
                                                     "elastic-level stresses", 0), 0u);
  c.separation.stress_fidelity = "complete";
  EXPECT_NE(stress_fidelity_warning(c, "beam").find("radial_crack and separation constants were fitted to "
                                                    "elastic and complete-level stresses"), std::string::npos);
  const std::string path = fitlib_test::temp_path("levels.json");
  c.separation.stress_fidelity = "";
  save_card(path, c);
  EXPECT_EQ(card_to_json(load_card(path)), card_to_json(c));
  EXPECT_FALSE(card_to_json(c)["modes"]["separation"].contains("stress_fidelity"));
}

TEST(FatigueCard, RoundTripWithCordBreak) {
  FatigueCard c = default_card();
  c.cord_break = CordBreakLaw{9.5, 0.01, 1500.0, 4.2, 0.1};
  c.reference_temperature_C = 95.0;
  const std::string path = fitlib_test::temp_path("round.json");
  save_card(path, c);
  EXPECT_EQ(card_to_json(load_card(path)), card_to_json(c));
}

void expect_error(const std::string& text, const std::string& key, int line = 0) {
  const std::string path = write("bad.json", text);
  try {
    load_card(path);
    FAIL() << "accepted: " << text;
  } catch (const core::InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
  }
}

TEST(FatigueCard, ErrorsNameFileAndKey) {
  nlohmann::json j = card_to_json(default_card());
  auto without = [&](const std::string& mode, const std::string& key) {
    nlohmann::json k = j;
    k["modes"][mode].erase(key);
    return k.dump();
  };
  expect_error(without("separation", "n"), "modes.separation.n");
  nlohmann::json k = j;
  k["modes"]["radial_crack"]["sigma0_MPa"] = "high";
  expect_error(k.dump(), "modes.radial_crack.sigma0_MPa");
  k = j;
  k["modes"]["radial_crack"]["sigma0_MPa"] = -1.0;
  expect_error(k.dump(), "modes.radial_crack.sigma0_MPa");
  k = j;
  k["modes"]["cord"] = nlohmann::json::object();
  expect_error(k.dump(), "modes.cord");
  k = j;
  k.erase("reference_temperature_C");
  expect_error(k.dump(), "reference_temperature_C");
  k = j;
  k["schema"] = "fitlib.card/1";
  expect_error(k.dump(), "schema");
  k = j;
  k["cord_break"] = {{"a", 9.0}, {"b_per_MPa", 0.01}, {"ultimate_MPa", 1500}};
  expect_error(k.dump(), "cord_break.cord_area_mm2");
  k = j;
  k["modes"]["radial_crack"]["sigma_0"] = 3.0;  // the message lists the keys the object takes
  try {
    card_from_json(k, "c.json");
    ADD_FAILURE() << "accepted sigma_0";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("takes b_per_C, covariance, n, scatter, sigma0_MPa, stress_fidelity"), std::string::npos)
        << e.what();
  }
  k = j;
  k["modes"]["separation"]["stress_fidelity"] = "fem";
  expect_error(k.dump(), "modes.separation.stress_fidelity");
  expect_error("{\n  \"schema\": \"fitlib.fatigue-card/1\",\n  \"name\": oops\n}\n", "", 3);
  EXPECT_THROW(load_card(fitlib_test::temp_path("missing.json")), core::InputError);
}

}  // namespace
}  // namespace fitlib::fatigue
