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
  EXPECT_EQ(c.radial_crack.stress_fidelity, core::Fidelity::complete);
  EXPECT_EQ(c.separation.stress_fidelity, core::Fidelity::complete);
  EXPECT_EQ(stress_fidelity_warning(c, core::Fidelity::complete), "");
  EXPECT_EQ(stress_fidelity_warning(c, core::Fidelity::beam).rfind("the fatigue card's radial_crack and separation constants "
                                                     "were fitted to complete-level stresses, and this run's "
                                                     "stresses are the beam level's", 0), 0u);
  c.radial_crack.stress_fidelity = core::Fidelity::elastic;
  c.separation.stress_fidelity = std::nullopt;
  EXPECT_EQ(stress_fidelity_warning(c, core::Fidelity::elastic), "");
  EXPECT_EQ(stress_fidelity_warning(c, core::Fidelity::beam).rfind("the fatigue card's radial_crack constants were fitted to "
                                                     "elastic-level stresses", 0), 0u);
  c.separation.stress_fidelity = core::Fidelity::complete;
  EXPECT_NE(stress_fidelity_warning(c, core::Fidelity::beam).find("radial_crack and separation constants were fitted to "
                                                    "elastic and complete-level stresses"), std::string::npos);
  const std::string path = fitlib_test::temp_path("levels.json");
  c.separation.stress_fidelity = std::nullopt;
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

// Constants per stress level (docs/fatigue.md §4 "One life scale for every level"): a run at a level
// takes that level's constants for every mode fitted at another level, keeps a mode fitted at its
// own level or stating none, and a card without the level is read as before.
TEST(FatigueCard, LevelsGiveEachRunTheConstantsOfItsOwnStresses) {
  FatigueCard c = default_card();
  c.levels.clear();
  LifeLaw beam1{50.0, 4.423, 0.02897, core::Fidelity::beam}, beam2{2.5, 11.69, 0.1466, core::Fidelity::beam};
  c.levels[core::Fidelity::beam] = LevelLaws{beam1, beam2};
  const FatigueCard at_beam = card_at_level(c, core::Fidelity::beam);
  EXPECT_EQ(at_beam.radial_crack.sigma0_MPa, 50.0);
  EXPECT_EQ(at_beam.separation.sigma0_MPa, 2.5);
  EXPECT_EQ(at_beam.separation.stress_fidelity, core::Fidelity::beam);
  EXPECT_TRUE(at_beam.levels.empty());
  EXPECT_EQ(stress_fidelity_warning(at_beam, core::Fidelity::beam), "");
  EXPECT_EQ(card_at_level(c, core::Fidelity::complete).radial_crack.sigma0_MPa, 104.218);  // the modes' own level
  EXPECT_NE(stress_fidelity_warning(card_at_level(c, core::Fidelity::elastic), core::Fidelity::elastic), "");  // no elastic entry: warned
  c.separation.stress_fidelity = std::nullopt;  // a mode that states no level is kept at every level
  EXPECT_EQ(card_at_level(c, core::Fidelity::beam).separation.sigma0_MPa, 4.21028);
  const std::string path = fitlib_test::temp_path("levels-round.json");
  save_card(path, c);
  EXPECT_EQ(card_to_json(load_card(path)), card_to_json(c));
  nlohmann::json j = card_to_json(c);
  j["levels"]["beam"]["separation"].erase("stress_fidelity");  // absent: the key's level
  EXPECT_EQ(card_from_json(j, "c.json").levels.at(core::Fidelity::beam).separation.stress_fidelity, core::Fidelity::beam);
  j["levels"]["beam"]["separation"]["stress_fidelity"] = "elastic";
  expect_error(j.dump(), "levels.beam.separation.stress_fidelity");
  j = card_to_json(c);
  j["levels"]["fem"] = j["levels"]["beam"];
  expect_error(j.dump(), "levels.fem");
  j = card_to_json(c);
  j["levels"]["beam"]["separation"]["n"] = -1.0;
  expect_error(j.dump(), "levels.beam.separation.n");
}

// The bundled card's beam and elastic constants come from scripts/calibrate-levels.sh, whose
// provenance names the drives, the date, the commit and the fitted stress factors.
TEST(FatigueCard, BundledCardHoldsTheCalibratedLevelsWithTheirProvenance) {
  const FatigueCard c = default_card();
  for (const core::Fidelity fidelity : {core::Fidelity::beam, core::Fidelity::elastic}) {
    const char* level = core::to_string(fidelity);
    ASSERT_TRUE(c.levels.count(fidelity)) << level;
    EXPECT_EQ(c.levels.at(fidelity).radial_crack.n, c.radial_crack.n) << "n held: a stress factor per level";
    EXPECT_EQ(c.levels.at(fidelity).separation.b_per_C, c.separation.b_per_C);
    const nlohmann::json& p = c.provenance.at("level_calibration").at(level);
    for (const char* mode : {"radial_crack", "separation"}) {
      // σ0 of the level = σ0 of the complete level / the stress factor (n and b held)
      const double factor = p.at("stress_factor").at(mode).get<double>();
      EXPECT_NEAR(c.levels.at(fidelity).law(*mode_from_string(mode)).sigma0_MPa * factor,
                  c.law(*mode_from_string(mode)).sigma0_MPa, 1e-9 * c.law(*mode_from_string(mode)).sigma0_MPa);
    }
  }
  const nlohmann::json& p = c.provenance.at("level_calibration");
  for (const char* key : {"script", "date", "fitlib_commit", "calibration_drives", "held_out_drives"})
    EXPECT_TRUE(p.contains(key)) << key;
}

}  // namespace
}  // namespace fitlib::fatigue
