// End to end for the other subcommands: belt scenes, surfaces, staged Fritzson fits, master
// curves — run as a user runs them.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace fs = std::filesystem;

TEST(BeltCli, ReferenceDriveWritesLoadHistoryAndSaysWhatRan) {
  const auto dir = temp_file("belt_out");
  const auto r = run_fitcli("belt --scene " + source_path("datasets/drives/ref-0500-heavy.toml") + " --out-dir " + dir + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir + "/load_history.csv"));
  const auto summary = nlohmann::json::parse(slurp(dir + "/summary.json"));
  int ran = 0, skipped = 0;
  for (const auto& e : summary["effects"]) (e["ran"].get<bool>() ? ran : skipped)++;
  EXPECT_GT(ran, 0);
  EXPECT_GT(skipped, 0);  // effects the scene did not ask for stay off
  const auto history = slurp(dir + "/load_history.csv");
  EXPECT_EQ(history.find("nan"), std::string::npos);
}

TEST(BeltCli, UnknownSceneKeyIsBadInputNamingTheKey) {
  const auto scene = temp_file("bad_scene.toml");
  std::ofstream(scene) << slurp(source_path("tests/data/scenes/minimal.toml")) << "\n[effects]\nwarp_drive = true\n";
  const auto r = run_fitcli("belt --scene " + scene + " --out-dir " + temp_file("bad_belt"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("warp_drive"), std::string::npos) << r.err;
}

TEST(SurfaceCli, ReportVShearDesignFitsWithConstraintsAndRefusesExtrapolation) {
  const auto out = temp_file("shear_surface.json");
  const auto r = run_fitcli("surface fit --data " + source_path("tests/data/surface/shear_3x3x3_missing.csv") +
                            " --x strain_amplitude --x frequency_Hz --x temperature_C --y storage_MPa --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto s = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(s["statistics"]["N"], 47);
  EXPECT_EQ(s["statistics"]["p"], 24);
  auto e = run_fitcli("surface eval --surface " + out + " --at 0.015,10,60");
  EXPECT_EQ(e.exit_code, 0) << e.err;
  e = run_fitcli("surface eval --surface " + out + " --at 0.5,10,60");  // amplitude far outside
  EXPECT_EQ(e.exit_code, 3) << e.err;
}

TEST(FritzsonCli, StagedFitOfMaterialTwoNamesWhatTheDataCannotDetermine) {
  const auto out = temp_file("material-2.json");
  const auto r = run_fitcli("fit --data " + source_path("datasets/materials/material-2.csv") +
                            " --model fritzson-iso --backend staged --schedule " +
                            source_path("datasets/schedules/fritzson-iso.json") + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto card = nlohmann::json::parse(slurp(out));
  EXPECT_LT(card["fit"]["mean_rel_error"].get<double>(), 0.02);
  const auto& ni = card["fit"]["identifiability"]["not_identifiable"];
  EXPECT_NE(std::find(ni.begin(), ni.end(), "C_d"), ni.end()) << ni.dump();
  const auto loops = temp_file("loops.csv");
  EXPECT_EQ(run_fitcli("material-point --card " + source_path("datasets/cards/material-1-true.json") +
                       " --case 7.3 --out " + loops).exit_code, 0);
  EXPECT_GT(slurp(loops).size(), 1000u);
}

TEST(FitCli, MasterCurveFromRawIsothermsWritesShifts) {
  const auto shifts = temp_file("shifts.csv"), out = temp_file("master-card.json");
  const auto r = run_fitcli("fit --data " + source_path("datasets/materials/pyvisco-freq-raw.csv") +
                            " --format pyvisco --model prony --terms 20 --master-curve --reference-c -5 --shifts-out " +
                            shifts + " --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto text = slurp(shifts);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 23);  // names, units, 21 isotherms
  EXPECT_EQ(text.rfind("T,log_aT\nC,-\n", 0), 0u);  // pyvisco shift-factor format
  const auto card = nlohmann::json::parse(slurp(out));
  EXPECT_EQ(card["temperature"]["law"], "wlf");
}
