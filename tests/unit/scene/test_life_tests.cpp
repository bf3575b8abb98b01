// Life tests (scene/life_tests.hpp): the CSV of drive scenes with observed lives, each scene run to
// its stresses, and the fatigue card fitted to them — against lives computed from a known card.
#include <gtest/gtest.h>

#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fatigue/life_fit.hpp"
#include "fitlib/scene/life_tests.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

using namespace fitlib;

namespace {
const std::string kDrives = FITLIB_SOURCE_DIR "/datasets/drives/";
const std::string kTruth = FITLIB_SOURCE_DIR "/datasets/life-tests/fatigue-truth.json";
const std::string kHeader =
    "case,scene,failure_mode,observed_cycles,conditions.temperature_C,drive.torque_Nm,"
    "drive.pulleys[0].pitch_diameter_mm,drive.pulleys[1].pitch_diameter_mm\n";

core::InputError parse_error(const std::string& text) {
  try {
    scene::parse_life_tests(text, kDrives + "tests.csv");
  } catch (const core::InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for\n" << text;
  return core::InputError("");
}

struct Case {
  double temperature_C, torque_Nm, diameter_mm;
};

// The medium drive with the case's keys and `card` as its fatigue card: the governing mode and its
// life in cycles, as a life test would have observed them.
std::pair<std::string, double> true_life(const Case& c, const std::string& card) {
  auto s = scene::load_scene(kDrives + "ref-0500-medium.toml");
  s.temperature_C = c.temperature_C;
  s.torque_Nm = c.torque_Nm;
  for (auto& p : s.pulleys) p.pitch_diameter_mm = c.diameter_mm;
  s.outputs["life"] = true;
  s.life = scene::LifeSpec{};
  s.life->card = card;
  const auto r = scene::run_scene(s);
  return {r.life->report.governing, r.life->report.life_cycles};
}

}  // namespace

TEST(LifeTests, ReadsScenesModesLivesAndSceneKeysRelativeToTheFile) {
  const auto tests = scene::parse_life_tests(
      kHeader + "A,ref-0500-medium.toml,separation,1e6,90,20,100,100\n# a comment\n"
                ",/abs/s.toml,radial_crack,2e7,,,80,80\n",
      kDrives + "tests.csv");
  ASSERT_EQ(tests.size(), 2u);
  EXPECT_EQ(tests[0].name, "A");
  EXPECT_EQ(tests[0].scene_path, kDrives + "ref-0500-medium.toml");
  EXPECT_EQ(tests[0].mode, fatigue::Mode::separation);
  EXPECT_EQ(tests[0].observed_cycles, 1e6);
  ASSERT_EQ(tests[0].scene_keys.size(), 4u);
  EXPECT_EQ(tests[0].scene_keys[0].first, "conditions.temperature_C");
  EXPECT_EQ(std::get<std::int64_t>(tests[0].scene_keys[0].second), 90);
  EXPECT_EQ(tests[1].name, "line 4");
  EXPECT_EQ(tests[1].scene_path, "/abs/s.toml");
  EXPECT_EQ(tests[1].scene_keys.size(), 2u);  // empty fields leave the scene's values
}

TEST(LifeTests, MalformedRowsNameFileLineColumnAndKey) {
  struct Bad {
    std::string text, key, message;
    int line, column;
  };
  const std::string row = "A,ref-0500-medium.toml,separation,1e6,90,20,100,100\n";
  for (const Bad& b : std::vector<Bad>{
           {"case,scene,failure_mode,observed_h,torque\n" + row, "torque", "unknown column 'torque'", 1, 5},
           {"scene,observed_h\nx,1\n", "failure_mode", "missing column 'failure_mode'", 1, 0},
           {"scene,failure_mode,observed_h,observed_cycles\nx,separation,1,2\n", "observed_h", "one of", 1, 0},
           {kHeader + "A,s.toml,peel,1e6,90,20,100,100\n", "failure_mode", "'peel'", 2, 3},
           {kHeader + "A,s.toml,separation,-5,90,20,100,100\n", "observed_cycles", "must be positive", 2, 4},
           {kHeader + "A,s.toml,separation,lots,90,20,100,100\n", "", "not a number", 2, 4},
           {kHeader + "A,,separation,1e6,90,20,100,100\n", "scene", "empty scene", 2, 2},
           {kHeader + "A,s.toml,separation,1e6\n", "", "row has 4 fields, header has 8", 2, 0},
           {kHeader, "", "no life tests", 1, 0},
           // --peaks-out groups rows by name: two belts under one name would merge
           {kHeader + row + "B" + row.substr(1) + row, "case", "'A' repeats the name of line 2", 4, 1}}) {
    const core::InputError e = parse_error(b.text);
    EXPECT_EQ(e.file(), kDrives + "tests.csv") << b.message;
    EXPECT_EQ(e.line(), b.line) << e.what();
    EXPECT_EQ(e.column(), b.column) << e.what();
    if (!b.key.empty()) {
      EXPECT_EQ(e.key(), b.key) << e.what();
    }
    EXPECT_NE(std::string(e.what()).find(b.message), std::string::npos) << e.what();
  }
}

// A scene that is missing, or that rejects a key's value, names the CSV's line and the key.
TEST(LifeTests, SceneFailuresNameTheCsvLineAndTheKey) {
  const std::string csv = kDrives + "tests.csv";
  auto observe = [&](const std::string& text) {
    try {
      scene::observe_life_tests(scene::parse_life_tests(text, csv), csv, fatigue::default_card());
    } catch (const core::InputError& e) {
      return e;
    }
    ADD_FAILURE() << "no error";
    return core::InputError("");
  };
  core::InputError e = observe(kHeader + "A,missing.toml,separation,1e6,90,20,100,100\n");
  EXPECT_EQ(e.file(), csv);
  EXPECT_EQ(e.line(), 2);
  EXPECT_NE(std::string(e.what()).find("missing.toml"), std::string::npos) << e.what();
  e = observe(kHeader + "A,ref-0500-medium.toml,separation,1e6,90,-20,100,100\n");
  EXPECT_EQ(e.line(), 2) << e.what();
  EXPECT_EQ(e.key(), "drive.torque_Nm") << e.what();
  e = observe("scene,failure_mode,observed_h,drive.nope.x\nref-0500-medium.toml,separation,1,3\n");
  EXPECT_EQ(e.line(), 2) << e.what();
  EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos) << e.what();
}

// Synthetic data of known truth: lives computed from fatigue-truth.json on 12 variants of the
// medium drive (beam level) are fitted from Report I's card; each mode's constants come back.
TEST(LifeTests, FitRecoversTheConstantsTheObservedLivesWereComputedFrom) {
  std::string csv = kHeader;
  int radial = 0;
  for (const Case& c : std::vector<Case>{{60, 2.5, 125}, {100, 2.5, 80}, {80, 5, 100}, {60, 5, 125}, {100, 10, 125},
                                         {60, 10, 80}, {80, 20, 100}, {100, 20, 125}, {60, 30, 100},
                                         {100, 30, 80}, {80, 2.5, 125}, {60, 2.5, 80}}) {
    const auto [mode, cycles] = true_life(c, kTruth);
    radial += mode == "radial_crack";
    char row[256];
    std::snprintf(row, sizeof row, "T%g-M%g-D%g,ref-0500-medium.toml,%s,%.17g,%g,%g,%g,%g\n", c.temperature_C,
                  c.torque_Nm, c.diameter_mm, mode.c_str(), cycles, c.temperature_C, c.torque_Nm, c.diameter_mm,
                  c.diameter_mm);
    csv += row;
  }
  ASSERT_GE(radial, 4);
  ASSERT_LE(radial, 8);
  // The source only places the scenes (nothing is read from it).
  const auto cases = scene::observed_cases(csv, kDrives + "tests.csv", fatigue::default_card());
  ASSERT_EQ(cases.size(), 12u);
  const fatigue::LifeCardFit fit = fatigue::fit_life_card(cases, fatigue::default_card());
  const fatigue::FatigueCard truth = fatigue::load_card(kTruth);
  ASSERT_EQ(fit.fits.size(), 2u);
  for (const auto& f : fit.fits) {
    const fatigue::LifeLaw& want = truth.law(f.mode);
    EXPECT_NEAR(f.law.sigma0_MPa / want.sigma0_MPa, 1.0, 1e-5) << fatigue::to_string(f.mode);
    EXPECT_NEAR(f.law.n / want.n, 1.0, 1e-5) << fatigue::to_string(f.mode);
    EXPECT_NEAR(f.law.b_per_C / want.b_per_C, 1.0, 1e-5) << fatigue::to_string(f.mode);
    EXPECT_LT(f.rms_log10_error, 1e-6);
  }
  EXPECT_EQ(fit.card.radial_crack.n, fit.fits[0].law.n);
  EXPECT_EQ(fit.card.reference_temperature_C, fatigue::default_card().reference_temperature_C);
  // Two runouts (failure_mode none), stopped at a third of the truth's shorter life: one case per
  // mode each, and the fit stays exact (as failures they would pull it off).
  for (const Case& c : std::vector<Case>{{80, 10, 80}, {100, 5, 100}}) {
    const double cycles = true_life(c, kTruth).second / 3.0;
    char row[256];
    std::snprintf(row, sizeof row, "R%g-M%g,ref-0500-medium.toml,none,%.17g,%g,%g,%g,%g\n", c.temperature_C,
                  c.torque_Nm, cycles, c.temperature_C, c.torque_Nm, c.diameter_mm, c.diameter_mm);
    csv += row;
  }
  const auto with_runouts = scene::observed_cases(csv, kDrives + "tests.csv", fatigue::default_card());
  ASSERT_EQ(with_runouts.size(), 16u);
  for (std::size_t k = 12; k < 16; ++k) EXPECT_TRUE(with_runouts[k].runout) << with_runouts[k].name;
  EXPECT_NE(with_runouts[12].mode, with_runouts[13].mode);
  const fatigue::LifeCardFit bounded = fatigue::fit_life_card(with_runouts, fatigue::default_card());
  for (const auto& f : bounded.fits) {
    EXPECT_EQ(f.runouts, 2) << fatigue::to_string(f.mode);
    EXPECT_NEAR(f.law.n / truth.law(f.mode).n, 1.0, 1e-5) << fatigue::to_string(f.mode);
    EXPECT_LT(f.rms_log10_error, 1e-6);
    EXPECT_TRUE(f.violated_runouts.empty());
  }
}
