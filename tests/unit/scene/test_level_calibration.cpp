// One life scale for every level (issue 33 item 3; docs/fatigue.md §4 "One life scale for every
// level"): the bundled fatigue card's beam and elastic constants, fitted by scripts/calibrate-levels.sh
// to the complete level's lives, put each level's life of a held-out drive within its factor of the
// complete level's, in the same governing mode; and the accelerated-test drives (datasets/drives/
// acc-0500-*, issue 33 item 2) run at the beam and elastic levels.
#include <gtest/gtest.h>
#include "common/temp_path.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

using namespace fitlib;

namespace {
const std::string kDrives = FITLIB_SOURCE_DIR "/datasets/drives/";
const std::string kCards = FITLIB_SOURCE_DIR "/datasets/cards/";

// The drive as fitcli life runs it: the beam level on the bare file (no cards: the level's default),
// the segment levels with the thesis cards (material 1 bottom, material 2 cushion), 2 load cycles.
scene::Scene drive_at(const std::string& drive, const std::string& level, int cycles = 2) {
  scene::Scene s = scene::load_scene(kDrives + drive + ".toml");
  s.outputs["life"] = true;
  if (level == "beam") return s;
  s.materials["bottom"] = kCards + "material-1-true.json";
  s.materials["cushion"] = kCards + "material-2-true.json";
  s.life = scene::LifeSpec{};
  s.life->fidelity = core::fidelity_from_string(level, "level"), s.life->cycles = cycles;
  return s;
}

bool off_scale(const scene::SceneResult& r) {
  for (const std::string& w : r.warnings)
    if (w.find("off the constants' scale") != std::string::npos) return true;
  return false;
}

const nlohmann::json& calibration() {
  static const fatigue::FatigueCard card = fatigue::default_card();
  return card.provenance.at("level_calibration");
}

std::vector<std::string> accelerated_drives() {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(kDrives))
    if (e.path().filename().string().rfind("acc-0500-", 0) == 0) out.push_back(e.path().stem().string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// The held-out drives (not among the calibration's): each level's governing life against the
// complete level's, as the calibration recorded it (scripts/calibrate-levels.sh runs the complete
// level; bench_life calibration recomputes all three). Goals of issue 33: beam within x3, elastic
// within x1.5, the same governing mode. The beam level reached only 0.14x on acc-0500-torque-15 until
// its body forces were read over one cog pitch with the bend's shear (2026-12-02: 0.38x; docs/decisions.md
// "Beam level: the body forces over one cog pitch, and the bend's shear").
TEST(LevelCalibration, HeldOutDrivesLiveWithinEachLevelsFactorOfTheCompleteLevelInTheSameMode) {
  const nlohmann::json& held = calibration().at("held_out_drives");
  ASSERT_EQ(held.size(), 2u);
  for (const auto& [drive, complete] : held.items()) {
    ASSERT_TRUE(complete.is_object()) << drive << ": the complete level did not complete in the calibration";
    const double life = std::min(complete.at("N1").get<double>(), complete.at("N2").get<double>());
    for (const auto& [level, factor] : {std::pair<const char*, double>{"beam", 3.0}, {"elastic", 1.5}}) {
      const scene::SceneResult r = scene::run_scene(drive_at(drive, level));
      const double ratio = r.life->report.life_cycles / life;
      EXPECT_LT(ratio, factor) << drive << " " << level;
      EXPECT_GT(ratio, 1.0 / factor) << drive << " " << level;
      EXPECT_EQ(r.life->report.governing, complete.at("governing").get<std::string>()) << drive << " " << level;
      EXPECT_FALSE(off_scale(r)) << drive << " " << level;
    }
  }
}

// Report I and III: light loads give radial cracks, heavy ones separation; the calibrated constants
// keep that at the beam and elastic levels (the complete level's modes: the calibration's record).
// Before the levels had their own constants the beam level said separation on the light drive.
TEST(LevelCalibration, LightDriveCracksRadiallyAndHeavyDriveSeparatesAtEveryLevel) {
  const nlohmann::json& drives = calibration().at("calibration_drives");
  EXPECT_EQ(drives.at("ref-0500-light").at("governing"), "radial_crack");
  EXPECT_EQ(drives.at("ref-0500-heavy").at("governing"), "separation");
  for (const char* level : {"beam", "elastic"}) {
    EXPECT_EQ(scene::run_scene(drive_at("ref-0500-light", level)).life->report.governing, "radial_crack") << level;
    EXPECT_EQ(scene::run_scene(drive_at("ref-0500-heavy", level)).life->report.governing, "separation") << level;
  }
}

// The README's tour (fitcli life --scene datasets/drives/ref-0500-heavy.toml: the beam level, no
// cards) reads the beam level's constants: no off-scale warning, and the life it would have had with
// Report I's complete-level constants is 2.6e3 x shorter than with the calibrated ones.
TEST(LevelCalibration, TheToursBeamRunReadsTheBeamLevelsConstants) {
  const scene::SceneResult r = scene::run_scene(drive_at("ref-0500-heavy", "beam"));
  EXPECT_FALSE(off_scale(r));
  fatigue::FatigueCard complete_only = fatigue::default_card();
  complete_only.levels.clear();
  scene::Scene s = drive_at("ref-0500-heavy", "beam");
  const std::string path = fitlib_test::temp_path("complete-only.json");
  fatigue::save_card(path, complete_only);
  s.life = scene::LifeSpec{};
  s.life->card = path;
  const scene::SceneResult uncalibrated = scene::run_scene(s);
  EXPECT_TRUE(off_scale(uncalibrated));
  const fatigue::FatigueCard beam = fatigue::card_at_level(fatigue::default_card(), core::Fidelity::beam);
  // n held: the life scales by the stress factor to the power n, exactly
  const double f2 = fatigue::default_card().separation.sigma0_MPa / beam.separation.sigma0_MPa;
  EXPECT_NEAR(r.life->report.modes[1].life_cycles / uncalibrated.life->report.modes[1].life_cycles,
              std::pow(f2, -beam.separation.n), 1e-9 * std::pow(f2, -beam.separation.n));
}

// Issue 33 item 2's drive set: every accelerated drive loads and gives finite lives at the beam level
// and at the elastic level (one load cycle here: finiteness, not the settled value).
TEST(AcceleratedDrives, EveryDriveGivesFiniteLivesAtTheBeamAndElasticLevels) {
  const std::vector<std::string> drives = accelerated_drives();
  EXPECT_GE(drives.size(), 8u);
  for (const std::string& d : drives)
    for (const char* level : {"beam", "elastic"}) {
      const scene::SceneResult r = scene::run_scene(drive_at(d, level, 1));
      for (const auto& m : r.life->report.modes) EXPECT_TRUE(std::isfinite(m.life_cycles)) << d << " " << level;
      EXPECT_TRUE(std::isfinite(r.life->report.life_h)) << d << " " << level;
    }
}

// Ready for issue 33 item 2 (the lead's): the complete level completes on every accelerated drive
// with the damage law read at every amplitude. Today (2026-12-02, main 53ad3b3's segment) all 13 stop
// in the first load cycle (NumericalError, exit 4 in fitcli: the fold); with the damage held 9 stop and
// acc-0500-pulley-120, slack-300, tension-700 and torque-15 pass. The flank knobs (radial foundation and
// stick together, at their derived values, x3 and x10; measured 2026-12-02) carry none of the 9 held
// or 13 extrapolated: each stop moves by 1-6 mm (docs/segment.md "The accelerated regime's fold";
// SegmentLife.BothFlankKnobsAtTenTimesTheirDerivedValuesDoNotCarryTheAcceleratedBaseDrive). Nor does
// the branch switch (SteppingOptions::branch_switch 0.01, measured 2026-12-02): with the law at every
// amplitude no stop has a negative eigenvalue to switch on; held, the switched increments advance λ
// by < 10⁻⁷ (SegmentLife.BranchSwitchFindsNoBifurcationAtTheAcceleratedBaseDrivesStop).
// Run with --gtest_also_run_disabled_tests.
TEST(AcceleratedDrives, DISABLED_CompleteLevelCompletesEveryDriveWithTheLawAtEveryAmplitude) {
  for (const std::string& d : accelerated_drives()) {
    scene::Scene s = drive_at(d, "complete");
    s.life->beyond_tests = scene::LifeSpec::BeyondTests::extrapolate;
    scene::SceneResult r;
    EXPECT_NO_THROW(r = scene::run_scene(s)) << d;
    if (r.life)
      for (const auto& m : r.life->report.modes) EXPECT_TRUE(std::isfinite(m.life_cycles)) << d;
  }
}

// What the accelerated regime's fold is (docs/segment.md "The accelerated regime's fold"): a
// stability limit of the section under Report I's dead contact loads that scales with the shear
// modulus of the bottom rubber (the cogs), not the cushion's, and is not a property of a card's law
// or damage. The base accelerated drive at the complete level with isotropic elastic cards (the
// contract's Hencky point, ν 0.49): E 8 / 1 MPa (bottom / cushion) runs the load cycle; E 2 / 4 MPa
// stops at the driving pulley (284.5 mm; E 2 / 1 MPa at 276.5 mm), at a side pressure below the
// largest the stiffer bottom carried. Measured 2026-12-04, not tested: E 4 / 2 runs, 4 / 1 stops at
// the driven pulley (747.6 mm), 1 / 4 at 186.2 mm. (A neo-Hooke card of the same moduli stops too.)
TEST(AcceleratedDrives, CompleteLevelsFoldIsAStabilityLimitOfTheBottomRubberNotOfTheCushion) {
  auto run = [](double bottom_E_MPa, double cushion_E_MPa) {
    scene::Scene s = drive_at("acc-0500-base", "complete", 1);
    for (const char* role : {"bottom", "cushion"}) {
      const double E = std::string(role) == "bottom" ? bottom_E_MPa : cushion_E_MPa;
      const std::string card = fitlib_test::temp_path(std::string("iso-") + role + "-" + std::to_string(E) + ".json");
      std::ofstream(card) << nlohmann::json{{"schema", "fitlib.card/1"}, {"model", "elastic-iso"}, {"name", role},
                                            {"parameters", {{{"name", "E"}, {"value", E}}, {{"name", "nu"}, {"value", 0.49}}}},
                                            {"temperature", {{"law", "none"}}}}.dump();
      s.materials[role] = card;
    }
    return s;
  };
  const scene::SceneResult stiff_bottom = scene::run_scene(run(8.0, 1.0));
  for (const auto& m : stiff_bottom.life->report.modes) EXPECT_TRUE(std::isfinite(m.life_cycles));
  try {
    scene::run_scene(run(2.0, 4.0));
    ADD_FAILURE() << "the E 2 / 4 MPa section ran the accelerated load cycle";
  } catch (const core::NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("failed in cycle 1 after path position 28"), std::string::npos) << what;  // 284.5 mm
    EXPECT_NE(what.find("a stability limit proportional to its rubber's shear modulus"), std::string::npos) << what;
  }
}
