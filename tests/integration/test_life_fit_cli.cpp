// fitcli life-fit: the bundled synthetic life tests (scenes run, observed hours) → a fatigue card
// whose 95 % intervals hold the truth the lives were made from; the card reads back in `life`;
// the stored peaks fit again to the same constants; the same command writes the same bytes.
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {
const std::string kTests = source_path("datasets/life-tests/synthetic-beam.csv");

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(slurp(path)); }
}  // namespace

TEST(LifeFitCli, BundledLifeTestsGiveACardWhoseIntervalsHoldTheTruth) {
  const std::string card = temp_file("life-fit-card.json"), peaks = temp_file("life-fit-peaks.csv");
  const auto r = run_fitcli("life-fit --observed " + kTests + " --out " + card + " --peaks-out " + peaks);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"radial_crack  11", "separation    19", "sigma0_MPa [95 %]", "beam level\n",
                           "card written to"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  EXPECT_NE(r.err.find("fitcli: warning: radial_crack: sigma0's 95 % interval"), std::string::npos) << r.err;
  const auto fitted = read_json(card), truth = read_json(source_path("datasets/life-tests/fatigue-truth.json"));
  for (const char* mode : {"radial_crack", "separation"})
    for (const char* constant : {"sigma0_MPa", "n", "b_per_C"}) {
      const auto ci = fitted["provenance"]["life_fit"][mode]["constants"][constant]["ci95"];
      const double want = truth["modes"][mode][constant];
      EXPECT_LE(ci[0].get<double>(), want) << mode << " " << constant;
      EXPECT_GE(ci[1].get<double>(), want) << mode << " " << constant;
    }
  EXPECT_EQ(fitted["provenance"]["observed"]["cases"], 30);
  for (const char* mode : {"radial_crack", "separation"})  // the scenes ran the beam level
    EXPECT_EQ(fitted["modes"][mode]["stress_fidelity"], "beam") << mode;

  // The card drives a life; the stored peaks fit again without the scenes, to the same constants.
  const std::string scene = temp_file("life-fit-scene.toml");
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-medium.toml")) << "\n[life]\ncard = \"" << card
                       << "\"\n";
  const auto life = run_fitcli("life --scene " + scene + " --json --out-dir " + temp_file("life-fit-life"));
  ASSERT_EQ(life.exit_code, 0) << life.err;
  EXPECT_EQ(nlohmann::json::parse(life.out)["modes"].size(), 2u);
  EXPECT_EQ(life.out.find("constants were fitted to"), std::string::npos) << life.out;  // a beam-level life
  EXPECT_NE(slurp(peaks).find(",stress_fidelity\n"), std::string::npos);
  const std::string again = temp_file("life-fit-again.json");
  ASSERT_EQ(run_fitcli("life-fit --observed " + peaks + " --out " + again).exit_code, 0);
  for (const char* mode : {"radial_crack", "separation"})
    for (const char* constant : {"sigma0_MPa", "n", "b_per_C"})
      EXPECT_NEAR(read_json(again)["modes"][mode][constant].get<double>() /
                      fitted["modes"][mode][constant].get<double>(), 1.0, 1e-9) << mode << " " << constant;
  EXPECT_EQ(read_json(again)["modes"]["separation"]["stress_fidelity"], "beam");  // kept by the stored peaks

  const std::string first = slurp(card);  // the same command again: the same bytes
  ASSERT_EQ(run_fitcli("life-fit --observed " + kTests + " --out " + card + " --peaks-out " + peaks).exit_code, 0);
  EXPECT_EQ(slurp(card), first);
}

// A file of runouts only (tests stopped without failing) fixes no constant: exit 3 naming the file and
// failure_mode, no card written (it was exit 4 "no failure mode could be fitted ()").
TEST(LifeFitCli, RunoutsAloneAreRefusedNamingTheFile) {
  const std::string observed = temp_file("runouts-only.csv"), card = temp_file("runouts-only.json");
  std::ofstream(observed) << "case,failure_mode,temperature_C,observed_cycles,peaks_MPa,runout\n"
                             "R1,separation,80,1e9,0.5,1\nR2,radial_crack,80,1e9,0.3,1\n";
  const auto r = run_fitcli("life-fit --observed " + observed + " --out " + card);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find(observed + ": key 'failure_mode': no life test failed (2 runout case(s))"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(card));
}

// --json keeps stdout one document, with the figure beside it (gnuplot speaks on stderr).
TEST(LifeFitCli, JsonCarriesTheCardAndItsWarnings) {
  const std::string png = temp_file("life-fit.png");
  const auto r = run_fitcli("life-fit --observed " + kTests + " --out " + temp_file("life-fit-json.json") +
                            " --json --plot " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(png).substr(0, 4), "\x89PNG");
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["schema"], "fitlib.fatigue-card/1");
  ASSERT_EQ(j["warnings"].size(), 1u);
  EXPECT_NE(j["warnings"][0].get<std::string>().find("radial_crack"), std::string::npos);
}
