// End to end: fit → card → eval → export, exit codes and determinism, as a user runs them.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "fitlib/card/card.hpp"

namespace {
const std::string kMaster = source_path("datasets/materials/pyvisco-freq-master.csv");
const std::string kSynthetic = source_path("datasets/materials/synthetic-prony-shear.csv");
}  // namespace

TEST(FitCli, PyviscoMasterCurveToCardAndEvalReproducesTheCardExactly) {
  const auto card_path = temp_file("master.json");
  const auto r = run_fitcli("fit --data " + kMaster + " --format pyvisco --model prony --terms auto --out " + card_path);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("GCV"), std::string::npos) << r.out;  // the smooth spectrum's lambda path is printed
  const auto card = fitlib::card::load_card(card_path);
  EXPECT_EQ(card.model_kind, "prony");
  EXPECT_EQ(card.model_options["mode"], "uniaxial");
  EXPECT_EQ(card.fit["n_points"], 206);
  for (const auto& p : card.parameters) EXPECT_GT(p.value, 0.0);

  const auto e = run_fitcli("eval --card " + card_path + " --mode uniaxial --frequency-hz 1e-10,0.001,1,1000,1e12");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto model = card.model();
  const auto p = card.values();
  std::istringstream lines(e.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "mode,orientation,frequency_Hz,temperature_C,strain_amplitude,storage_MPa,loss_MPa,tan_delta,mean_modulus_MPa");
  int n = 0;
  for (double f : {1e-10, 0.001, 1.0, 1000.0, 1e12}) {
    ASSERT_TRUE(std::getline(lines, line));
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    fitlib::model::TestCondition c;
    c.mode = fitlib::model::TestMode::uniaxial;
    c.frequency_Hz = f;
    const auto m = model->moduli(p.data(), c);
    EXPECT_EQ(std::stod(cells[5]), m.storage) << line;  // bit-exact
    EXPECT_EQ(std::stod(cells[6]), m.loss) << line;
    ++n;
  }
  EXPECT_EQ(n, 5);
}

TEST(FitCli, SameInputAndSeedGiveIdenticalCardBytes) {
  const auto a = temp_file("det_a.json"), b = temp_file("det_b.json");
  for (const auto& out : {a, b}) {
    const auto r = run_fitcli("fit --data " + kSynthetic + " --model prony --terms 6 --backend ceres --seed 7 --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  // The command line differs only in the output path; compare everything else.
  auto ja = nlohmann::json::parse(slurp(a)), jb = nlohmann::json::parse(slurp(b));
  ja["provenance"].erase("command");
  jb["provenance"].erase("command");
  EXPECT_EQ(ja.dump(), jb.dump());
}

TEST(FitCli, SyntheticTableRecoversTheTrueParameters) {
  const auto truth = fitlib::card::load_card(source_path("datasets/cards/synthetic-prony-shear-true.json"));
  const auto out = temp_file("synthetic.json");
  const auto r = run_fitcli("fit --data " + kSynthetic + " --model prony --terms 6 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto fitted = fitlib::card::load_card(out);
  ASSERT_EQ(fitted.parameters.size(), truth.parameters.size());
  int inside = 0;
  for (size_t i = 0; i < truth.parameters.size(); ++i) {
    const auto& f = fitted.parameters[i];
    ASSERT_TRUE(f.ci95_low && f.ci95_high) << i;
    if (*f.ci95_low <= truth.parameters[i].value && truth.parameters[i].value <= *f.ci95_high) ++inside;
    EXPECT_NEAR(f.value, truth.parameters[i].value, 0.25 * truth.parameters[i].value) << i;
  }
  EXPECT_GE(inside, 10);  // of 13: 95 % intervals, 1 % noise
}

TEST(FitCli, BundledSyntheticTableIsReproducedByteForByte) {
  const auto out = temp_file("regenerated.csv");
  const auto r = run_fitcli("synth --card " + source_path("datasets/cards/synthetic-prony-shear-true.json") +
                            " --frequency-hz " + "0.001,0.00316227766016838,0.01,0.0316227766016838,0.1,0.316227766016838,1,3.16227766016838,10,31.6227766016838,100,316.227766016838,1000" +
                            " --specimens 3 --noise 0.01 --seed 42 --name synthetic-prony-shear --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(out), slurp(kSynthetic));
}

TEST(FitCli, ExitCodesFollowTheContract) {
  const auto bad_dir = source_path("tests/data/malformed");
  auto r = run_fitcli("fit --data " + kSynthetic + " --model no-such-model");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("unknown model"), std::string::npos) << r.err;
  r = run_fitcli("fit --model prony");  // missing --data
  EXPECT_EQ(r.exit_code, 2);
  const auto broken_card = temp_file("broken-card.json");
  std::ofstream(broken_card) << R"({"schema": "fitlib.card/1", "model": "prony", "options": {"terms": 1},
  "parameters": [{"name": "G_inf", "value": 1}, {"name": "G_1", "value": 1}, {"name": "tau_1", "value": -2}]})";
  r = run_fitcli("eval --card " + broken_card + " --frequency-hz 1");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("parameters[2].value"), std::string::npos) << r.err;
}

TEST(FitCli, ExportWritesSolverKeywordsOrRefusesClearly) {
  const auto card_path = temp_file("export.json");
  ASSERT_EQ(run_fitcli("fit --data " + kSynthetic + " --model prony --terms 6 --out " + card_path).exit_code, 0);
  const auto inp = temp_file("mat.inp");
  auto r = run_fitcli("export --card " + card_path + " --format abaqus --out " + inp);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(inp).find("*VISCOELASTIC, TIME=PRONY"), std::string::npos);
  r = run_fitcli("export --card " + card_path + " --format lsdyna --out " + temp_file("mat.k"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("at most 5 Prony terms"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(temp_file("mat.k")).good());  // nothing half-written
}

// As many free parameters as data values (or more): the fit passes through the data, so its tiny
// errors say nothing; the verdict warns and the card's quality is not acceptable, on a hand-typed
// relaxation table (7 values: 3 terms are 7 parameters; the relaxation path had no such warning) and
// a three-frequency table (6 values; 4 terms kept at 9 free parameters after a re-polish with the
// times held, whose 5 free ones hid it).
TEST(FitCli, AFitWithNoResidualDegreesOfFreedomIsAWarning) {
  const std::string relax = temp_file("dof-relax.csv"), dynamic = temp_file("dof-dynamic.csv");
  std::ofstream(relax) << "t,E_relax\ns,MPa\n0.001,12.1\n0.01,9.8\n0.1,7.4\n1,5.9\n10,5.1\n100,4.8\n1000,4.7\n";
  std::ofstream(dynamic) << "mode,frequency_Hz,temperature_C,storage_MPa,loss_MPa\n"
                            "shear,1,23,2.0,0.3\nshear,10,23,2.5,0.4\nshear,100,23,3.1,0.45\n";
  auto fit = [](const std::string& data, const std::string& options) {
    const std::string card = temp_file("dof-card.json");
    const auto r = run_fitcli("fit --data " + data + " --model prony " + options + " --out " + card);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return std::make_pair(r, nlohmann::json::parse(slurp(card))["fit"]["quality"]);
  };
  for (const auto& [data, options, said] :
       {std::tuple<std::string, std::string, std::string>{relax, "--format pyvisco --terms 3",
                                                          "the data do not determine the card: 7 residuals for 7 free parameters"},
        {dynamic, "--terms 4", "the data do not determine the card: 6 residuals for 9 free parameters"}}) {
    const auto [r, quality] = fit(data, options);
    EXPECT_NE(r.err.find("warning: " + said), std::string::npos) << r.err;
    EXPECT_FALSE(quality["acceptable"].get<bool>()) << quality.dump();
  }
  const auto [two, quality] = fit(relax, "--format pyvisco --terms 2");  // 5 parameters: residual freedom
  EXPECT_EQ(two.err.find("do not determine the card"), std::string::npos) << two.err;
  EXPECT_TRUE(quality["acceptable"].get<bool>()) << quality.dump();
}

// A card whose fit did not pass its quality verdict says so wherever it is read: eval, synth and
// export on stderr, the solver deck in comment lines of at most 80 characters, a scene among its
// warnings (once per role). Before, only `fit` said it; the card then went silently into decks.
TEST(FitCli, ACardThatFailedItsQualityVerdictSaysSoWhereverItIsRead) {
  const std::string table = temp_file("poor.csv"), card = temp_file("poor.json");
  std::ofstream(table) << "mode,frequency_Hz,temperature_C,storage_MPa,loss_MPa\n"
                          "shear,1,23,2.0,0.3\nshear,10,23,2.5,0.4\nshear,100,23,3.1,0.45\n";
  ASSERT_EQ(run_fitcli("fit --data " + table + " --model prony --terms 4 --out " + card).exit_code, 0);
  const std::string said = "the card's fit did not pass its quality verdict (1 warning(s) in fit.quality.warnings";
  for (const std::string& command :
       {"eval --card " + card + " --frequency-hz 10", "synth --card " + card + " --frequency-hz 10 --out " +
                                                            temp_file("poor-synth.csv"),
        "export --card " + card + " --format abaqus"}) {
    const auto r = run_fitcli(command);
    EXPECT_EQ(r.exit_code, 0) << command << ": " << r.err;
    EXPECT_NE(r.err.find("warning: " + said), std::string::npos) << command << ": " << r.err;
  }
  const auto deck = run_fitcli("export --card " + card + " --format lsdyna --density 1.2e-9").out;
  EXPECT_NE(deck.find("$ WARNING: the card's fit did not pass"), std::string::npos) << deck;
  std::istringstream lines(deck);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("$", 0) == 0) EXPECT_LE(line.size(), 80u) << line;
  const std::string scene = temp_file("poor-scene.toml");
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-light.toml")) << "\n[belt.materials]\nbottom = \""
                       << card << "\"\n[life]\nfidelity = \"beam\"\n";
  const auto life = run_fitcli("life --scene " + scene + " --json --out-dir " + temp_file("poor-life"));
  ASSERT_EQ(life.exit_code, 0) << life.err;
  int times = 0;
  const auto result = nlohmann::json::parse(life.out);
  for (const auto& w : result["warnings"])
    times += w.get<std::string>().find("(bottom): " + said) != std::string::npos;
  EXPECT_EQ(times, 1) << life.out;
}

// A relaxation table's fit speaks of M(t) and of times: the term table's rms column is M(t)'s (no
// loss column), the summary's rms is M(t)'s, and the worst row is named by its time (it said
// "storage …, loss 0" and "max 4.63 % at 0.0159155 Hz" for a table of times).
TEST(FitCli, ARelaxationFitSpeaksOfMOfTAndTimes) {
  const std::string relax = temp_file("relax-words.csv");
  std::ofstream(relax) << "t,E_relax\ns,MPa\n0.001,12.1\n0.01,9.8\n0.1,7.4\n1,5.9\n10,5.1\n100,4.8\n1000,4.7\n";
  const auto r = run_fitcli("fit --data " + relax + " --format pyvisco --model prony --terms auto --out " +
                            temp_file("relax-words.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* said : {"rms_M(t)", "rms log10 error of M(t) ", "relaxation (all): mean relative error",
                           "% at t = 10 s"})
    EXPECT_NE(r.out.find(said), std::string::npos) << said << "\n" << r.out;
  for (const char* not_said : {"rms_E''", "loss 0", " Hz\n"}) EXPECT_EQ(r.out.find(not_said), std::string::npos) << not_said;
  // The parameters' shared reason is said once, then "as above" (it filled every one of 28 lines).
  const auto reason = std::string("(standard errors are not estimated for relaxation fits)");
  const auto first = r.out.find(reason);
  ASSERT_NE(first, std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(reason, first + 1), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(as above)"), std::string::npos) << r.out;
}

// A damage card has no Prony form: export refuses (exit 2) and names the route, which works: the
// card evaluated at one temperature and amplitude, fitted by a Prony card, exports.
TEST(FitCli, ADamageCardsExportNamesTheRouteThroughSynthAndFit) {
  const std::string card = source_path("datasets/cards/material-2-true.json");
  const auto refused = run_fitcli("export --card " + card + " --format abaqus");
  EXPECT_EQ(refused.exit_code, 2);
  for (const char* said : {"cannot hold amplitude dependence", "fitcli synth --card CARD", "--model prony"})
    EXPECT_NE(refused.err.find(said), std::string::npos) << said << "\n" << refused.err;
  const std::string table = temp_file("damage-route.csv"), prony = temp_file("damage-route.json");
  ASSERT_EQ(run_fitcli("synth --card " + card + " --temperature-c 80 --amplitude 0.01 --frequency-hz 3,10,34,60 --out " +
                       table).exit_code, 0);
  ASSERT_EQ(run_fitcli("fit --data " + table + " --model prony --terms auto --out " + prony).exit_code, 0);
  const auto deck = run_fitcli("export --card " + prony + " --format abaqus");
  ASSERT_EQ(deck.exit_code, 0) << deck.err;
  EXPECT_NE(deck.out.find("*VISCOELASTIC, TIME=PRONY"), std::string::npos) << deck.out;
}

// export --temperature-c reads the card where every other command would: beyond its data window
// it is refused naming the window's key (exit 3), with --allow-extrapolation it is a warning; inside,
// the deck has no shift law and says at which temperature it holds.
TEST(FitCli, ExportAtOneTemperatureKeepsToTheCardsDataWindow) {
  const std::string card = temp_file("export_window.json");
  ASSERT_EQ(run_fitcli("fit --data " + source_path("datasets/materials/synthetic-prony-wlf.csv") +
                       " --model prony --terms 6 --temperature-law wlf --reference-c 23 --out " + card).exit_code, 0);
  const auto refused = run_fitcli("export --card " + card + " --format abaqus --temperature-c 120");
  EXPECT_EQ(refused.exit_code, 3) << refused.err;
  EXPECT_NE(refused.err.find("fit.data_window.temperature_C"), std::string::npos) << refused.err;
  const auto allowed = run_fitcli("export --card " + card + " --format abaqus --temperature-c 120 --allow-extrapolation");
  ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_NE(allowed.err.find("extrapolating: --temperature-c 120"), std::string::npos) << allowed.err;
  const auto inside = run_fitcli("export --card " + card + " --format ansys --temperature-c 60");
  ASSERT_EQ(inside.exit_code, 0) << inside.err;
  EXPECT_EQ(inside.out.find("TB,SHIFT"), std::string::npos) << inside.out;
  EXPECT_NE(inside.out.find("! at 60 degC only"), std::string::npos) << inside.out;
  EXPECT_NE(run_fitcli("export --card " + card + " --format ansys").out.find("TB,SHIFT"), std::string::npos);
}

TEST(FitCli, LsDynaExportWritesTheGivenDensityOrRefuses) {
  const auto card_path = temp_file("export_dyna.json");
  ASSERT_EQ(run_fitcli("fit --data " + kSynthetic + " --model prony --terms 3 --out " + card_path).exit_code, 0);
  const auto deck = temp_file("dyna.k");
  auto r = run_fitcli("export --card " + card_path + " --format lsdyna --out " + deck);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--density"), std::string::npos) << r.err;
  EXPECT_FALSE(std::ifstream(deck).good());
  r = run_fitcli("export --card " + card_path + " --format lsdyna --density 1.2e-9 --out " + deck);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(deck).find("*MAT_GENERAL_VISCOELASTIC\n$ MID, RO, BULK, PCF, EF, TREF, A, B\n1,1.2e-09,"),
            std::string::npos) << slurp(deck);
}

TEST(FitCli, EveryMalformedTableExitsWithThreeAndNamesFileAndLine) {
  const std::string dir = source_path("tests/data/malformed");
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const auto name = entry.path().filename().string();
    if (name.rfind("accepted_", 0) == 0 || entry.path().extension() != ".csv") continue;
    const auto r = run_fitcli("fit --data " + entry.path().string() + " --model prony --terms 1 --mode shear");
    EXPECT_EQ(r.exit_code, 3) << name << ": " << r.err;
    EXPECT_NE(r.err.find(name + ":"), std::string::npos) << name << ": " << r.err;  // file:line[:column]
    ++checked;
  }
  EXPECT_GE(checked, 15);
}
