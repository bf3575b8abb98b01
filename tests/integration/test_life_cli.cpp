// fitcli life end to end on every bundled reference drive: finite lives and a governing mode,
// life.json in the output folder equal to --json, bad scenes exit 3, the elastic level runs the segment.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {
std::string unique_dir(const std::string& name) {
  return temp_file(name + "-" + std::to_string(getpid()));
}

// The bundled Report I card with both modes' constants stated to be of `level`'s stresses, and
// without its other levels' constants ("levels").
std::string fatigue_card_of_level(const std::string& level) {
  nlohmann::json card = nlohmann::json::parse(slurp(source_path("datasets/cards/fatigue-fritzson-1988.json")));
  card.erase("levels");
  for (const char* mode : {"radial_crack", "separation"}) card["modes"][mode]["stress_fidelity"] = level;
  const std::string path = unique_dir("fatigue_" + level) + ".json";
  std::ofstream(path) << card.dump(2);
  return path;
}
}  // namespace

// Constants fitted to one level's stresses read at another: the life is off their scale, so the
// table, life.json and summary.json warn, naming both levels; a card of the run's level does not.
// (The bundled card has beam-level constants too, docs/fatigue.md §4: a card of complete-level
// constants alone is read here.)
TEST(LifeCli, ConstantsFittedAtAnotherLevelAreAWarning) {
  const std::string drive = source_path("datasets/drives/ref-0500-light.toml");  // the beam level
  const std::string warning = "the fatigue card's radial_crack and separation constants were fitted to "
                              "complete-level stresses, and this run's stresses are the beam level's";
  const std::string out = unique_dir("life_level_out");
  const std::string scene = unique_dir("life_level_complete") + ".toml";
  std::ofstream(scene) << slurp(drive) << "\n[life]\ncard = \"" << fatigue_card_of_level("complete") << "\"\n";
  const auto builtin = run_fitcli("life --scene " + scene + " --out-dir " + out);
  ASSERT_EQ(builtin.exit_code, 0) << builtin.err;
  // on stderr, as every command's warnings (docs/cli.md "Conventions")
  EXPECT_NE(builtin.err.find("fitcli: warning: " + warning), std::string::npos) << builtin.err;
  EXPECT_EQ(builtin.out.find("WARNING"), std::string::npos) << builtin.out;
  for (const char* file : {"/life.json", "/summary.json"}) {
    const std::string text = slurp(out + file);
    EXPECT_NE(text.find(warning), std::string::npos) << file;
  }
  const std::string copy = unique_dir("life_level") + ".toml";
  std::ofstream(copy) << slurp(drive) << "\n[life]\ncard = \"" << fatigue_card_of_level("beam") << "\"\n";
  const auto beam = run_fitcli("life --scene " + copy + " --out-dir " + unique_dir("life_level_beam_out") + " --json");
  ASSERT_EQ(beam.exit_code, 0) << beam.err;
  EXPECT_EQ(beam.out.find("constants were fitted to"), std::string::npos) << beam.out;
  const auto a = nlohmann::json::parse(slurp(out + "/life.json")), b = nlohmann::json::parse(beam.out);
  EXPECT_EQ(a["modes"], b["modes"]);  // the stated level changes no number
}

TEST(LifeCli, EveryReferenceDriveHasFiniteLivesAndAGoverningMode) {
  for (const char* load : {"light", "medium", "heavy", "severe"}) {
    const std::string dir = unique_dir(std::string("life_") + load);
    const std::string scene = source_path("datasets/drives/ref-0500-" + std::string(load) + ".toml");
    const auto r = run_fitcli("life --scene " + scene + " --out-dir " + dir + " --json");
    ASSERT_EQ(r.exit_code, 0) << load << ": " << r.err;
    const auto j = nlohmann::json::parse(slurp(dir + "/life.json"));
    EXPECT_EQ(j, nlohmann::json::parse(r.out)) << load;
    ASSERT_EQ(j["modes"].size(), 2u) << load;
    for (const auto& m : j["modes"]) {
      ASSERT_TRUE(m["life_cycles"].is_number()) << load << " " << m["mode"];
      EXPECT_TRUE(std::isfinite(m["life_cycles"].get<double>()) && m["life_cycles"].get<double>() > 0) << load;
      EXPECT_GT(m["life_h"].get<double>(), 0.0) << load;
      EXPECT_FALSE(m["design_point"]["name"].get<std::string>().empty()) << load;
    }
    const std::string governing = j["governing_mode"];
    EXPECT_TRUE(governing == "radial_crack" || governing == "separation") << load << ": " << governing;
    EXPECT_EQ(j["fidelity"], "beam");
    int ran = 0;
    for (const auto& e : j["effects"]) {
      ran += e["ran"].get<bool>();
      EXPECT_FALSE(e.contains("wall_s"));  // only with --record-timing
    }
    EXPECT_GE(ran, 5) << load;  // stiffness, drive, contact_arcs, beam_stresses, fatigue
  }
}

TEST(LifeCli, HumanTableNamesModesGoverningModeAndCosts) {
  const std::string dir = unique_dir("life_table");
  const auto r = run_fitcli("life --scene " + source_path("datasets/drives/ref-0500-heavy.toml") +
                            " --out-dir " + dir + " --record-timing");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"radial_crack", "separation", "governing: separation", "design point", " h)",
                           "ran     fatigue", "ran     beam_stresses", " ms  (", "sha256"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
  const auto j = nlohmann::json::parse(slurp(dir + "/life.json"));
  EXPECT_TRUE(j["effects"][0].contains("wall_s"));
}

TEST(LifeCli, RepeatedRunsWriteIdenticalBytes) {
  const std::string a = unique_dir("life_a"), b = unique_dir("life_b");
  const std::string scene = source_path("datasets/drives/ref-0500-medium.toml");
  ASSERT_EQ(run_fitcli("life --scene " + scene + " --out-dir " + a).exit_code, 0);
  ASSERT_EQ(run_fitcli("life --scene " + scene + " --out-dir " + b).exit_code, 0);
  EXPECT_EQ(slurp(a + "/life.json"), slurp(b + "/life.json"));
  EXPECT_EQ(slurp(a + "/summary.json"), slurp(b + "/summary.json"));
  EXPECT_EQ(slurp(a + "/stress_history.csv"), slurp(b + "/stress_history.csv"));
}

TEST(LifeCli, BadSceneIsBadInputNamingFileAndKey) {
  const std::string base = slurp(source_path("datasets/drives/ref-0500-heavy.toml"));
  const std::string bad = unique_dir("life_bad") + ".toml";
  std::ofstream(bad) << base << "\n[life]\nfidelity = \"fine\"\n";
  auto r = run_fitcli("life --scene " + bad + " --out-dir " + unique_dir("life_bad_out"));
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("life.fidelity"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(bad), std::string::npos) << r.err;
  r = run_fitcli("life --scene " + unique_dir("missing") + ".toml");
  EXPECT_EQ(r.exit_code, 3) << r.err;
}

// The elastic level: the segment FE driven by the light drive's load cycle (coarse mesh), then
// fatigue on its gap-bottom and cushion histories; the report names the segment effect.
TEST(LifeCli, ElasticLevelRunsTheSegmentOnTheLoadCycle) {
  const std::string base = slurp(source_path("datasets/drives/ref-0500-light.toml"));
  const std::string scene = unique_dir("life_segment") + ".toml";
  std::ofstream(scene) << base
                       << "\n[segment]\nfine_size_mm = 1.0\ncoarse_size_mm = 2.5\ncentral_pitches = 1.0\n"
                          "end_pitches = 1.0\ncushion_rows = 1\n[segment.materials]\n"
                          "bottom = {E_MPa = 20, nu = 0.49}\ncushion = {E_MPa = 8, nu = 0.49}\n"
                          "[life]\nfidelity = \"elastic\"\ncycles = 2\n";
  const std::string out = unique_dir("life_segment_out");
  const auto r = run_fitcli("life --scene " + scene + " --json --out-dir " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["fidelity"], "elastic") << r.out;
  EXPECT_NE(r.out.find("segment_fe"), std::string::npos);
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  // stress_history.csv reads back: every separation peak of life.json is the effective stress
  // (6.25-6.26 on the longitudinal plane: sigma = s11, tau = s12) of the design point's row at its time.
  std::istringstream csv(slurp(out + "/stress_history.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "point,role,x_mm,y_mm,t_s,s11_MPa,s22_MPa,s12_MPa,e11,e22,e12");
  std::vector<std::vector<std::string>> rows;
  while (std::getline(csv, line)) {
    rows.emplace_back();
    std::stringstream row(line);
    for (std::string c; std::getline(row, c, ',');) rows.back().push_back(c);
    ASSERT_EQ(rows.back().size(), 11u) << line;
    for (int k = 8; k < 11; ++k) EXPECT_TRUE(std::isfinite(std::stod(rows.back()[k]))) << line;  // the strains
  }
  const auto& separation = j["modes"][1];
  ASSERT_EQ(separation["mode"], "separation");
  const std::string design = separation["design_point"]["name"];
  ASSERT_FALSE(separation["peaks"].empty());
  for (const auto& peak : separation["peaks"]) {
    int found = 0;
    for (const auto& c : rows)
      if (c[0] == design && std::stod(c[4]) == peak["t_s"].get<double>()) {
        const double s11 = std::stod(c[5]), s12 = std::stod(c[7]);
        const double effective = s11 >= 0.0 ? std::hypot(s11, s12) : std::abs(s12);
        EXPECT_NEAR(effective, peak["effective_stress_MPa"].get<double>(), 1e-12 * effective) << c[4];
        ++found;
      }
    EXPECT_EQ(found, 1) << design << " at t " << peak["t_s"];
  }
  // life.json holds each design point's effective stress over the last cycle, the curve its peaks
  // were counted on: every peak is a sample of it, the largest peak its maximum.
  for (const auto& mode : j["modes"]) {
    const auto& t = mode["effective_stress"]["t_s"];
    const auto& s = mode["effective_stress"]["MPa"];
    ASSERT_EQ(t.size(), s.size());
    ASSERT_GT(t.size(), 50u) << mode["mode"];
    double largest_peak = 0.0;
    for (const auto& peak : mode["peaks"]) {
      std::size_t k = 0;
      while (k < t.size() && t[k].get<double>() != peak["t_s"].get<double>()) ++k;
      ASSERT_LT(k, t.size()) << mode["mode"] << " peak at " << peak["t_s"];
      EXPECT_EQ(s[k].get<double>(), peak["effective_stress_MPa"].get<double>());
      largest_peak = std::max(largest_peak, peak["effective_stress_MPa"].get<double>());
    }
    EXPECT_EQ(*std::max_element(s.begin(), s.end()), largest_peak) << mode["mode"];
  }
  const auto summary = nlohmann::json::parse(slurp(out + "/summary.json"));
  EXPECT_FALSE(summary["life"]["modes"][0].contains("effective_stress"));  // the summary stays short
}


// The segment levels report their built-in equilibrium check (docs/segment.md "Cord-line reactions
// and the belt force") in life.json under "segment_equilibrium", with its bounds, and in the table;
// --field-at entrance writes the stress field where the first pulley's side pressure starts.
TEST(LifeCli, ElasticLevelReportsTheSegmentEquilibriumCheckAndTheEntranceField) {
  const std::string base = slurp(source_path("datasets/drives/ref-0500-light.toml"));
  const std::string scene = unique_dir("life_equilibrium") + ".toml", out = unique_dir("life_equilibrium_out");
  std::ofstream(scene) << base
                       << "\n[segment]\nfine_size_mm = 1.0\ncoarse_size_mm = 2.5\ncentral_pitches = 1.0\n"
                          "end_pitches = 1.0\ncushion_rows = 1\n[segment.materials]\n"
                          "bottom = {E_MPa = 20, nu = 0.49}\ncushion = {E_MPa = 8, nu = 0.49}\n"
                          "[life]\nfidelity = \"elastic\"\ncycles = 1\ncard = \"" << fatigue_card_of_level("elastic") << "\"\n";
  const auto r = run_fitcli("life --scene " + scene + " --out-dir " + out + " --field-at entrance");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("segment equilibrium: error "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("stress field at entrance"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("WARNING"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("life's default segment"), std::string::npos) << r.out;  // the scene's [segment] mesh
  const auto j = nlohmann::json::parse(slurp(out + "/life.json"));
  ASSERT_TRUE(j.contains("segment_equilibrium")) << j.dump(2);
  const auto& e = j["segment_equilibrium"];
  for (const char* key : {"equilibrium_error", "span_cord_share", "span_section_mismatch"}) {
    const double value = e[key].get<double>(), bound = e[std::string(key) + "_bound"].get<double>();
    EXPECT_TRUE(std::isfinite(value)) << key;
    EXPECT_GE(value, 0.0) << key;
    EXPECT_LE(value, bound) << key;
  }
  EXPECT_EQ(e["span_cord_share_bound"].get<double>(), 1e-2);  // the life's sheared end faces
  EXPECT_EQ(e["span_section_mismatch_bound"].get<double>(), 1e-6);
  EXPECT_GT(e["span_increments"].get<int>(), 0);  // the span checks saw increments
  EXPECT_TRUE(e["within_bounds"].get<bool>());
  // The field: a legacy VTK with the cell stresses, at the first load-history row with side pressure.
  ASSERT_EQ(j["fields"].size(), 1u) << j.dump(2);
  EXPECT_EQ(j["fields"][0]["at"], "entrance");
  const std::string vtk = slurp(out + "/" + j["fields"][0]["file"].get<std::string>());
  EXPECT_EQ(vtk.rfind("# vtk DataFile Version 3.0", 0), 0u);
  EXPECT_NE(vtk.find("SCALARS sigma_xx_MPa double 1"), std::string::npos);
  EXPECT_EQ(vtk.find("nan"), std::string::npos);
  std::istringstream history(slurp(out + "/load_history.csv"));
  std::string line;
  std::getline(history, line);  // s_mm,t_s,pulley,zone,F_N,K_1_per_mm,p_MPa,...
  double first_contact = -1.0;
  while (first_contact < 0.0 && std::getline(history, line)) {
    std::vector<std::string> cell;
    std::stringstream row(line);
    for (std::string c; std::getline(row, c, ',');) cell.push_back(c);
    if (std::stod(cell.at(6)) > 0.0) first_contact = std::stod(cell.at(0));
  }
  EXPECT_NEAR(j["fields"][0]["s_mm"].get<double>(), first_contact, 1e-6);
  // The beam level has no segment run and no check.
  std::ofstream(scene) << base << "\n[life]\nfidelity = \"beam\"\n";
  const auto beam = run_fitcli("life --scene " + scene + " --json --out-dir " + out);
  ASSERT_EQ(beam.exit_code, 0) << beam.err;
  EXPECT_FALSE(nlohmann::json::parse(beam.out).contains("segment_equilibrium"));
}

// A bad --field-at is a usage error (exit 2) that leaves no output folder behind: a word that is
// neither "entrance" nor a number is refused before the folder is made, a position beyond the load
// cycle (known only once the cycle is computed) removes the folder the command made; a folder that
// existed before stays with its content.
// --plot draws the run's figure beside life.json, whose --json document stays alone on stdout; a
// run that fails writes no figure and leaves an existing one as it was.
TEST(LifeCli, PlotDrawsTheFigureAndAFailedRunLeavesNone) {
  const std::string dir = unique_dir("life_plot"), png = dir + ".png";
  const auto r = run_fitcli("life --scene " + source_path("datasets/drives/ref-0500-medium.toml") + " --out-dir " + dir +
                            " --json --plot " + png);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // the beam level's calibrated constants give the complete level's mode (docs/fatigue.md §4)
  EXPECT_EQ(nlohmann::json::parse(r.out)["governing_mode"], "radial_crack");
  EXPECT_EQ(slurp(png).substr(0, 4), "\x89PNG");
  std::ofstream(png, std::ios::trunc) << "mine\n";
  const auto bad = run_fitcli("life --scene " + source_path("tests/data/bad/scene/life_segment_ok.toml") +
                              " --field-at 1e9 --out-dir " + unique_dir("life_plot_bad") + " --plot " + png);
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_EQ(slurp(png), "mine\n");
}

TEST(LifeCli, BadFieldAtExitsTwoAndLeavesNoOutputFolder) {
  const std::string scene = source_path("tests/data/bad/scene/life_segment_ok.toml");
  for (const char* at : {"banana", "-3", "1e9"}) {
    const std::string out = unique_dir(std::string("life_field_") + (at[0] == '-' ? "neg" : at));
    const auto r = run_fitcli("life --scene " + scene + " --field-at " + at + " --out-dir " + out);
    EXPECT_EQ(r.exit_code, 2) << at << ": " << r.err;
    EXPECT_NE(r.err.find(std::string("'") + at + "'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("entrance"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << at << " left " << out;
  }
  const std::string kept = unique_dir("life_field_kept");
  std::filesystem::create_directories(kept);
  std::ofstream(kept + "/mine.txt") << "keep\n";
  const auto r = run_fitcli("life --scene " + scene + " --field-at 1e9 --out-dir " + kept);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(slurp(kept + "/mine.txt"), "keep\n");
  std::filesystem::remove_all(kept);
  // --out DIR (the issue's spelling; --out is a file everywhere else) is a usage error naming --out-dir.
  const std::string folder = unique_dir("life_out_spelling");
  const auto out = run_fitcli("life --scene " + scene + " --out " + folder);
  EXPECT_EQ(out.exit_code, 2) << out.err;
  EXPECT_NE(out.err.find("use --out-dir " + folder), std::string::npos) << out.err;
  EXPECT_FALSE(std::filesystem::exists(folder));
}

// The complete level on the medium drive with the thesis cards stops in cycle 1 on the ungraded
// 144-element mesh (docs/segment.md "Cost", complete level; the graded life mesh passes this one
// cycle by its increments and stops at the same place with two): exit 4,
// the message says where in the cycle (path position and the load there), the solver's step and
// node, why (a fold: with [life] diagnose_failure the stiffness's lowest eigenvalue at the best
// iterate is nearly zero, 1.8e-3 of 2e5 N/mm², its mode at the land), and what runs instead; no output
// folder is left.
TEST(LifeCli, CompleteLevelFailureOnTheMediumDriveSaysWhereWhyAndWhatRuns) {
  const std::string scene = unique_dir("life_complete_medium") + ".toml";
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-medium.toml"))
                       << "\n[belt.materials]\nbottom = \"" << source_path("datasets/cards/material-1-true.json")
                       << "\"\ncushion = \"" << source_path("datasets/cards/material-2-true.json")
                       << "\"\n[life]\nfidelity = \"complete\"\ncycles = 1\ndiagnose_failure = true\n"
                       << "[segment]\nfine_size_mm = 1.0\ncoarse_size_mm = 2.5\ncentral_pitches = 1\nend_pitches = 1\n"
                          "cushion_rows = 1\ngap_size_mm = 0\nrow_growth = 1\n";  // ungraded: the graded mesh passes one cycle
  const std::string out = unique_dir("life_complete_medium_out");
  const auto r = run_fitcli("life --scene " + scene + " --out-dir " + out);
  EXPECT_EQ(r.exit_code, 4) << r.err;
  for (const char* part : {"segment load cycle: failed in cycle 1 after path position", "side pressure",
                           "Newton failed in load increment", "largest residual at node", "The load path folds: under Report I's dead contact loads",
                           "lowest eigenvalues of K's symmetric part", "[life] fidelity = \"elastic\" runs",
                           "a card fitted to its table (fitcli fit) holds the damage"})
    EXPECT_NE(r.err.find(part), std::string::npos) << part << " in: " << r.err;
  EXPECT_EQ(r.err.find("diagnose_failure = true adds"), std::string::npos) << r.err;  // it did
  const std::string key = "lowest eigenvalues of K's symmetric part ";
  const std::size_t best = r.err.find(key, r.err.find("[best iterate]"));
  ASSERT_NE(best, std::string::npos) << r.err;
  const std::size_t largest = r.err.find("(largest ", best);
  ASSERT_NE(largest, std::string::npos) << r.err;
  EXPECT_LT(std::stod(r.err.substr(best + key.size())) / std::stod(r.err.substr(largest + 9)), 1e-7) << r.err;
  EXPECT_EQ(r.err.find("nan"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// The complete level holds a card's damage at the drivers its tests reached (fit.data_window.
// damage_driver, written by fit; here the thesis cards with the window of their synthetic tables:
// shear to 0.045, uniaxial to 0.015 and 0.01). So held, the medium drive passes both cycles, where the
// law extrapolated to the cushion's shear amplitude of ~0.9 folds the land in cycle 2; the table
// says what was held, and damage_hold = false brings the fold back with its remedy named.
// The [belt.materials] lines of the thesis cards with the window of their synthetic tables.
std::string windowed_cards(const std::string& tag) {
  const double shear = 0.045 / std::sqrt(2.0), fibre = std::sqrt(2.0) * 0.01;
  std::string cards;
  for (const auto& [role, material, drivers] :
       {std::tuple<const char*, const char*, nlohmann::json>{"bottom", "material-1", {shear, fibre, shear}},
        {"cushion", "material-2", {shear}}}) {
    nlohmann::json card = nlohmann::json::parse(slurp(source_path(std::string("datasets/cards/") + material + "-true.json")));
    card["fit"]["data_window"] = {{"strain_amplitude", {0.001, 0.045}}, {"damage_driver", drivers}};
    const std::string path = unique_dir(tag + "_" + material) + ".json";
    std::ofstream(path) << card.dump(2);
    cards += std::string(role) + " = \"" + path + "\"\n";
  }
  return cards;
}

TEST(LifeCli, CompleteLevelHoldsTheDamageAtTheTestedDriversAndPassesTheMediumDrive) {
  const std::string cards = windowed_cards("held");
  const std::string drive = slurp(source_path("datasets/drives/ref-0500-medium.toml"));
  for (const bool hold : {true, false}) {
    const std::string scene = unique_dir(std::string("life_held_") + (hold ? "on" : "off")) + ".toml";
    std::ofstream(scene) << drive << "\n[belt.materials]\n" << cards << "[life]\nfidelity = \"complete\"\ncycles = 2\n"
                         << (hold ? "" : "beyond_tests = \"extrapolate\"\n");
    const std::string out = unique_dir(std::string("life_held_out_") + (hold ? "on" : "off"));
    const auto r = run_fitcli("life --scene " + scene + " --out-dir " + out);
    if (!hold) {
      EXPECT_EQ(r.exit_code, 4) << r.err;
      for (const char* part : {"The load path folds: under Report I's dead contact loads", "[life] beyond_tests = \"hold\" (the default) holds"})
        EXPECT_NE(r.err.find(part), std::string::npos) << part << " in: " << r.err;
      continue;
    }
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto life = nlohmann::json::parse(slurp(out + "/life.json"));
    for (const auto& m : life["modes"]) EXPECT_TRUE(std::isfinite(m["life_cycles"].get<double>())) << m.dump();
    EXPECT_EQ(life["governing_mode"], "radial_crack");
    // Beyond the tests (docs/fatigue.md §8): the cushion's shear of ~0.9 is ~20x the window's 0.045, so
    // the separation life says so, flagged, and prints two significant digits.
    EXPECT_EQ(life["beyond_tests"], "hold");
    ASSERT_EQ(life["cards_read"].size(), 2u) << life.dump();
    const auto& cushion = life["cards_read"][1];
    EXPECT_EQ(cushion["role"], "cushion");
    EXPECT_TRUE(cushion["frequency_Hz"].is_null());  // the complete level: the full model, no one frequency
    EXPECT_EQ(cushion["largest_tested_strain_amplitude"], 0.045);
    EXPECT_NEAR(cushion["beyond_tests_factor"].get<double>(),
                cushion["reached_strain_amplitude"].get<double>() / 0.045, 1e-12);
    EXPECT_GT(cushion["beyond_tests_factor"].get<double>(), 5.0);
    const auto& separation = life["modes"][1];
    EXPECT_EQ(separation["mode"], "separation");
    EXPECT_TRUE(separation["extrapolated"].get<bool>());
    EXPECT_NE(separation["beyond_tests"].get<std::string>().find("cushion read at "), std::string::npos);
    const std::size_t row = r.out.find("\nseparation ") + 1;
    ASSERT_NE(row, 0u) << r.out;
    const std::string line = r.out.substr(row, r.out.find('\n', row) - row);
    const std::size_t cycles = line.find(" cycles (");
    ASSERT_NE(cycles, std::string::npos) << line;
    const std::string number = line.substr(line.find_first_not_of(' ', 10), cycles - line.find_first_not_of(' ', 10));
    const std::string mantissa = number.substr(0, number.find('e'));
    EXPECT_LE(std::count_if(mantissa.begin(), mantissa.end(), [](char c) { return std::isdigit(c) != 0; }), 2) << line;
    EXPECT_NE(r.out.find("beyond the tests: cushion read at "), std::string::npos) << r.out;
    // What the stresses came from (the complete level: 120 planned steps per cycle, 60 in the cycle
    // before the last), in the JSON and the text.
    const auto& run = life["segment_run"];
    EXPECT_EQ(run["elements"], 192);
    EXPECT_EQ(run["cycles"], 2);
    EXPECT_EQ(run["steps_per_cycle"], 120);
    EXPECT_EQ(run["conditioning_steps"], 60);
    EXPECT_GE(run["increments"].get<int>(), 4 + 60 + 120);
    EXPECT_NE(r.out.find("2 load cycle(s) of 120 planned steps (60 in each before the last), "), std::string::npos) << r.out;
    EXPECT_GT(run["newton_iterations"].get<int>(), run["increments"].get<int>());
    EXPECT_GE(run["cuts"].get<int>(), 0);
    for (const char* part : {"(bottom): its damage is held at the drivers its tests reached (fit.data_window.damage_driver "
                             "0.0318, 0.0141, 0.0318)", "(cushion): its damage is held at the drivers its tests reached",
                             "beyond_tests = \"extrapolate\" runs the law", "(the segment drove it at 0.",
                             "note: the complete level on the life's default segment (192 elements, 27 mm long, graded "
                             "at the central gap, one cushion row, sheared end faces), with the cards' damage held",
                             "segment FE material (the card's full model, damage held at its tests' drivers)"})
      EXPECT_NE((r.out + r.err).find(part), std::string::npos) << part << " in: " << r.out << r.err;  // warnings: stderr
  }
}

// [life] beyond_tests = "refuse" (docs/decisions.md "Life: one policy for a card driven beyond its
// tests"): the medium drive drives both windowed cards beyond 0.045, so the life is refused, exit 3,
// naming the key and each card with its factor, and no output is left.
TEST(LifeCli, BeyondTestsRefuseExitsThreeNamingTheKey) {
  const std::string scene = unique_dir("life_refuse") + ".toml";
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-medium.toml")) << "\n[belt.materials]\n"
                       << windowed_cards("refuse") << "[life]\nfidelity = \"elastic\"\ncycles = 1\n"
                       << "elastic_amplitude = \"small\"\nbeyond_tests = \"refuse\"\n";
  const std::string out = unique_dir("life_refuse_out");
  const auto r = run_fitcli("life --scene " + scene + " --out-dir " + out);
  EXPECT_EQ(r.exit_code, 3) << r.err;
  for (const char* part : {"life.beyond_tests", "the segment drove a card beyond its tests", "cushion read at ",
                           "x its largest tested amplitude", "\"hold\" holds the damage"})
    EXPECT_NE(r.err.find(part), std::string::npos) << part << " in: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(out + "/life.json"));
}

// The elastic level folds too where the side pressure is high: the medium drive with a 40 mm
// driver (R 20 mm, 4.3 MPa) stops in cycle 1, and the message says why it may and what runs
// (it ended at the node's residual: a user was left with exit 4 and no next step).
TEST(LifeCli, ElasticLevelFailureOnASmallPulleySaysWhyAndWhatRuns) {
  const std::string scene = unique_dir("life_elastic_40mm") + ".toml";
  std::string drive = slurp(source_path("datasets/drives/ref-0500-medium.toml"));
  const std::string driver = "pitch_diameter_mm = 100, role = \"driver\"";
  ASSERT_NE(drive.find(driver), std::string::npos);
  drive.replace(drive.find(driver), driver.size(), "pitch_diameter_mm = 40, role = \"driver\"");
  std::ofstream(scene) << drive << "\n[belt.materials]\nbottom = \"" << source_path("datasets/cards/material-1-true.json")
                       << "\"\ncushion = \"" << source_path("datasets/cards/material-2-true.json") << "\"\n[life]\ncycles = 1\n";
  const std::string out = unique_dir("life_elastic_40mm_out");
  const auto r = run_fitcli("life --scene " + scene + " --out-dir " + out);
  EXPECT_EQ(r.exit_code, 4) << r.err;
  for (const char* part : {"segment load cycle: failed in cycle 1", "curvature 0.05 1/mm", "a stability limit proportional to its rubber's shear modulus",
                           "diagnose_failure = true adds", "[life] fidelity = \"beam\" gives"})
    EXPECT_NE(r.err.find(part), std::string::npos) << part << " in: " << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));
}

// A shear Prony card without a bulk modulus (the README tour's card, one isotherm at 23 °C) in a
// drive at 80 °C: the scene converts it as eval and export do (K from G0 and [belt.materials]
// poisson_ratio, which the segment's K follows), and warns that it reads the card beyond its data
// window, in the table and in life.json (docs/decisions.md "Scenes: a card without a bulk modulus").
TEST(LifeCli, ShearCardWithoutBulkModulusRunsByThePoissonRatioAndWarnsBeyondItsDataWindow) {
  const std::string table = unique_dir("life_shear_table") + ".csv";
  std::ofstream(table) << "mode,frequency_Hz,temperature_C,storage_MPa,loss_MPa\n"
                          "shear,0.1,23,2.0,0.15\nshear,0.3,23,2.1,0.25\nshear,1,23,2.3,0.38\nshear,3,23,2.6,0.50\n"
                          "shear,10,23,3.0,0.52\nshear,30,23,3.3,0.45\nshear,100,23,3.5,0.35\n";
  const std::string card = unique_dir("life_shear_card") + ".json";
  ASSERT_EQ(run_fitcli("fit --data " + table + " --model prony --terms 3 --out " + card).exit_code, 0);
  auto run = [&](const std::string& poisson) {
    const std::string scene = unique_dir("life_shear" + std::to_string(poisson.size())) + ".toml";
    std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-light.toml")) << "\n[belt.materials]\nbottom = \""
                         << card << "\"\ncushion = \"" << card << "\"\n" << poisson
                         << "\n[segment]\nfine_size_mm = 1.0\ncoarse_size_mm = 2.5\ncentral_pitches = 1\nend_pitches = 1\n"
                            "cushion_rows = 1\n[life]\nfidelity = \"elastic\"\ncycles = 2\n";
    return run_fitcli("life --scene " + scene + " --out-dir " + unique_dir("life_shear_out") + " --json");
  };
  const auto r = run("");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  // Per role (bottom and cushion): the temperature beyond the card's, and the strain amplitude the
  // card's small-amplitude table does not give.
  // The built-in card's elastic-level constants are read (no off-scale warning: docs/fatigue.md §4).
  ASSERT_EQ(j["warnings"].size(), 4u) << r.out;
  int temperature = 0, amplitude = 0, level = 0;
  for (const auto& w : j["warnings"]) {
    const std::string text = w.get<std::string>();
    level += text.find("fitted to complete-level stresses, and this run's stresses are the elastic level's") !=
             std::string::npos;
    temperature += text.find("temperature_C 80 is outside its data window [23, 23] (fit.data_window.temperature_C)") !=
                   std::string::npos;
    amplitude += text.find("holds no strain amplitude") != std::string::npos;
  }
  EXPECT_EQ(temperature, 2) << r.out;
  EXPECT_EQ(amplitude, 2) << r.out;
  EXPECT_EQ(level, 0) << r.out;
  const double N1 = j["modes"][0]["life_cycles"], N2 = j["modes"][1]["life_cycles"];
  EXPECT_TRUE(std::isfinite(N1) && std::isfinite(N2) && N1 > 0.0 && N2 > 0.0) << r.out;
  // The segment's bulk modulus follows the ratio: a compressible 0.45 moves the lives.
  const auto compressible = run("poisson_ratio = 0.45");
  ASSERT_EQ(compressible.exit_code, 0) << compressible.err;
  const auto jc = nlohmann::json::parse(compressible.out);
  EXPECT_GT(std::abs(jc["modes"][0]["life_cycles"].get<double>() / N1 - 1.0), 0.01) << compressible.out;
  const auto bad = run("poisson_ratio = 0.5");
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_NE(bad.err.find("belt.materials.poisson_ratio"), std::string::npos) << bad.err;
}

// A static section case needs no drive: bend-40mm without its [drive] table gives `fitcli segment`
// the same points; `belt` and `life` on it exit 3 naming the missing table.
TEST(SegmentCli, StaticCaseNeedsNoDriveAndTheDriveCommandsSaySo) {
  const std::string text = slurp(source_path("datasets/segment/bend-40mm.toml"));
  const std::size_t drive = text.find("[drive]"), belt = text.find("[belt]");
  ASSERT_NE(drive, std::string::npos);
  const std::string scene = unique_dir("segment_no_drive") + ".toml";
  std::ofstream(scene) << text.substr(0, drive) + text.substr(belt);
  const auto with = run_fitcli("segment --scene " + source_path("datasets/segment/bend-40mm.toml") + " --json");
  const auto without = run_fitcli("segment --scene " + scene + " --json");
  ASSERT_EQ(with.exit_code, 0) << with.err;
  ASSERT_EQ(without.exit_code, 0) << without.err;
  EXPECT_EQ(nlohmann::json::parse(without.out)["points"], nlohmann::json::parse(with.out)["points"]);
  for (const char* command : {"belt", "life"}) {
    const auto r = run_fitcli(std::string(command) + " --scene " + scene + " --out-dir " + unique_dir("no_drive_out"));
    EXPECT_EQ(r.exit_code, 3) << command;
    EXPECT_NE(r.err.find("key 'drive': missing [drive] table"), std::string::npos) << command << ": " << r.err;
  }
}

// A bend tighter than the section can take: the reference section in neo-Hookean rubber fails
// near an 18 mm radius, where the gaps' land (4.1 mm below the cord line) is compressed to a
// nominal stretch of 0.77 and creases. Exit 4 says so with the stretch of the asked bend; a
// 30 mm bend on the same coarse mesh passes.
TEST(SegmentCli, ABendTighterThanTheLandCanTakeSaysTheLandCreases) {
  std::string text = slurp(source_path("datasets/segment/bend-40mm.toml"));
  text.replace(text.find("steps = 4"), 9, "steps = 4\nfine_size_mm = 1.0\ncoarse_size_mm = 2.5");
  auto bend = [&](const std::string& radius) {
    std::string t = text;
    t.replace(t.find("radius_mm = 40"), 14, "radius_mm = " + radius);
    const std::string scene = unique_dir("segment_bend_" + radius) + ".toml";
    std::ofstream(scene) << t;
    return run_fitcli("segment --scene " + scene);
  };
  const auto tight = bend("14");
  EXPECT_EQ(tight.exit_code, 4) << tight.out;
  for (const char* said : {"Newton failed", "The bend to radius 14 mm compresses the gaps' land, 4.1 mm below the "
                           "cord line, to a nominal stretch of about 0.714", "creases"})
    EXPECT_NE(tight.err.find(said), std::string::npos) << said << "\n" << tight.err;
  const auto wide = bend("30");
  EXPECT_EQ(wide.exit_code, 0) << wide.err;
}

// fitcli segment takes the scene's [belt.materials] cards (their elastic equivalents at the scene's
// temperature and [segment] frequency_Hz): an elastic-iso card pair (E 30 and 5 MPa, not [segment]'s
// default 20 and 8) gives the stresses of the same E and nu in [segment.materials] (the contract's Hencky point against the segment's own Hencky law);
// the output names where each material came from; a card without a frequency to read it at, or a
// role given twice, is refused at its key. (The cards were ignored before: a scene naming the bundled
// cards gave the stresses of [segment]'s default E 20 / 8 MPa.)
TEST(SegmentCli, StaticCaseRunsTheScenesCardsAndSaysWhereEachMaterialCameFrom) {
  const std::string dir = unique_dir("segment_cards");
  std::filesystem::create_directories(dir);
  for (const auto& [name, E] : {std::pair<std::string, double>{"iso30", 30.0}, {"iso5", 5.0}})
    std::ofstream(dir + "/" + name + ".json")
        << R"({"schema": "fitlib.card/1", "name": ")" << name
        << R"(", "model": "elastic-iso", "options": {}, "parameters": [{"name": "E", "value": )" << E
        << R"(}, {"name": "nu", "value": 0.49}]})";
  const std::string load = "[segment]\nstrain = 0.01\nradius_mm = 40\npressure_MPa = 0.3\nfine_size_mm = 1.0\n";
  const std::string head = "name = \"cards\"\n[belt]\nsection = \"cogged-0.500\"\n";
  const std::string cards = "[belt.materials]\nbottom = \"iso30.json\"\ncushion = \"iso5.json\"\n";
  std::ofstream(dir + "/cards.toml") << head << cards << load << "frequency_Hz = 10\n";
  std::ofstream(dir + "/plain.toml") << head << load
                                     << "[segment.materials]\nbottom = {E_MPa = 30, nu = 0.49}\n"
                                        "cushion = {E_MPa = 5, nu = 0.49}\n";
  std::ofstream(dir + "/no-frequency.toml") << head << cards << load;
  std::ofstream(dir + "/twice.toml") << head << cards << load << "frequency_Hz = 10\n[segment.materials]\n"
                                     << "cushion = {E_MPa = 8, nu = 0.49}\n";
  const auto with_cards = run_fitcli("segment --scene " + dir + "/cards.toml --json");
  const auto plain = run_fitcli("segment --scene " + dir + "/plain.toml --json");
  ASSERT_EQ(with_cards.exit_code, 0) << with_cards.err;
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  const auto a = nlohmann::json::parse(with_cards.out), b = nlohmann::json::parse(plain.out);
  ASSERT_EQ(a["points"].size(), b["points"].size());
  for (std::size_t k = 0; k < a["points"].size(); ++k)
    for (const char* c : {"sigma11_radial_MPa", "sigma22_longitudinal_MPa", "sigma12_MPa"}) {
      const double x = a["points"][k][c], y = b["points"][k][c];
      EXPECT_NEAR(x, y, 1e-9 * (1.0 + std::abs(y))) << a["points"][k]["name"] << " " << c;
    }
  EXPECT_EQ(a["materials"][0]["source"], dir + "/iso30.json");
  EXPECT_EQ(a["materials"][1]["source"], dir + "/iso5.json");
  EXPECT_EQ(a["cards_read_at"]["frequency_Hz"], 10.0);
  EXPECT_EQ(b["materials"][0]["source"], "[segment.materials]");
  EXPECT_FALSE(b.contains("cards_read_at"));
  const auto text = run_fitcli("segment --scene " + dir + "/cards.toml");
  EXPECT_NE(text.out.find("bottom: elastic-iso (" + dir + "/iso30.json)"), std::string::npos) << text.out;
  const auto no_frequency = run_fitcli("segment --scene " + dir + "/no-frequency.toml");
  EXPECT_EQ(no_frequency.exit_code, 3);
  EXPECT_NE(no_frequency.err.find("key 'segment.frequency_Hz'"), std::string::npos) << no_frequency.err;
  const auto twice = run_fitcli("segment --scene " + dir + "/twice.toml");
  EXPECT_EQ(twice.exit_code, 3);
  EXPECT_NE(twice.err.find("key 'segment.materials.cushion'"), std::string::npos) << twice.err;
}

// The segment levels compare the strain amplitude they drove each card at (half the range of the
// log strains over the last cycle at the role's monitored points) with the card's data window: a
// card fitted at 1 % strain is read at several per cent in the gap and the cushion, and the table
// and life.json say so for both roles (material 1 and 2's fitted cards: 8 % and 88 % at the light
// drive's complete level, windows ending at 4.5 %).
TEST(LifeCli, SegmentLevelsWarnWhenTheyDriveACardBeyondItsStrainWindow) {
  const std::string table = unique_dir("life_amplitude_table") + ".csv";
  std::ofstream(table) << "mode,frequency_Hz,temperature_C,strain_amplitude,storage_MPa,loss_MPa\n"
                          "shear,0.1,80,0.01,2.0,0.15\nshear,1,80,0.01,2.3,0.38\nshear,10,80,0.01,3.0,0.52\n"
                          "shear,100,80,0.01,3.5,0.35\n";
  const std::string card = unique_dir("life_amplitude_card") + ".json";
  ASSERT_EQ(run_fitcli("fit --data " + table + " --model prony --terms 2 --reference-c 80 -q --out " + card).exit_code, 0);
  const std::string scene = unique_dir("life_amplitude") + ".toml";
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-light.toml")) << "\n[belt.materials]\nbottom = \""
                       << card << "\"\ncushion = \"" << card << "\"\n"
                       << "\n[segment]\nfine_size_mm = 1.0\ncoarse_size_mm = 2.5\ncentral_pitches = 1\nend_pitches = 1\n"
                          "cushion_rows = 1\n[life]\nfidelity = \"elastic\"\ncycles = 2\n";
  const auto r = run_fitcli("life --scene " + scene + " --out-dir " + unique_dir("life_amplitude_out") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  int beyond = 0;
  for (const auto& w : j["warnings"]) {
    const std::string text = w.get<std::string>();
    if (text.find("strain_amplitude") == std::string::npos) continue;
    ++beyond;
    EXPECT_NE(text.find(" its data window [0.01, 0.01] (fit.data_window.strain_amplitude)"), std::string::npos)
        << text;
    // One warning per role: the amplitudes read (the belt's stiffness at 0.5 and 4.5 %, the segment's
    // own) as one range; the highest is the segment's.
    const auto dots = text.find(" … ");
    const double a = std::stod(text.substr(dots == std::string::npos ? text.find("strain_amplitude ") + 17 : dots + 5));
    EXPECT_GT(a, 0.045) << text;  // bending alone strains the gap by several per cent
    EXPECT_LT(a, 2.0) << text;
  }
  EXPECT_EQ(beyond, 2) << r.out;  // bottom and cushion, one each
  EXPECT_EQ(r.out.find("holds no strain amplitude"), std::string::npos) << r.out;

  // The same table without its amplitude column: the card's strain range is not known, and the
  // segment drove it far beyond 1 % (docs/decisions.md "Life: a card without strain amplitudes
  // driven beyond 1 % is a warning").
  std::ofstream(table) << "mode,frequency_Hz,temperature_C,storage_MPa,loss_MPa\nshear,0.1,80,2.0,0.15\n"
                          "shear,1,80,2.3,0.38\nshear,10,80,3.0,0.52\nshear,100,80,3.5,0.35\n";
  ASSERT_EQ(run_fitcli("fit --data " + table + " --model prony --terms 2 --reference-c 80 -q --out " + card).exit_code, 0);
  const auto linear = run_fitcli("life --scene " + scene + " --out-dir " + unique_dir("life_linear_out") + " --json");
  ASSERT_EQ(linear.exit_code, 0) << linear.err;
  int unknown = 0;
  const auto linear_json = nlohmann::json::parse(linear.out);
  for (const auto& w : linear_json["warnings"]) {
    const std::string text = w.get<std::string>();
    if (text.find("holds no strain amplitude") == std::string::npos) continue;
    ++unknown;
    const double a = std::stod(text.substr(text.find("drove it at ") + 12));
    EXPECT_GT(a, 0.045) << text;
    EXPECT_NE(text.find("the life is that of a rubber that does not soften"), std::string::npos) << text;
  }
  EXPECT_EQ(unknown, 2) << linear.out;
}

// A hand-typed three-pulley drive with the bundled cards, as a new user writes it: --plot may go into
// the --out-dir the run makes, and every WARNING of the table is in life.json and summary.json (the
// segment's span check warned in the table only).
TEST(LifeCli, EveryWarningOfTheTableIsInTheJsonAndThePlotMayGoIntoTheOutputFolder) {
  const std::string scene = unique_dir("life_three") + ".toml", out = unique_dir("life_three_out");
  std::ofstream(scene) << "name = \"hand-typed three-pulley drive\"\n[drive]\npulleys = [\n"
                          "  {name = \"motor\", pitch_diameter_mm = 112, role = \"driver\", speed_rpm = 1450, center_mm = [0, 0]},\n"
                          "  {name = \"fan\", pitch_diameter_mm = 180, role = \"driven\", center_mm = [300, 0]},\n"
                          "  {name = \"idler\", pitch_diameter_mm = 70, role = \"idler\", center_mm = [150, 90]} ]\n"
                          "torque_Nm = 12\ninitial_tension_N = 500\n[belt]\nsection = \"cogged-0.500\"\n"
                          "wedge_half_angle_deg = 19\ndensity_kg_m3 = 1200\n[belt.materials]\nbottom = \""
                       << source_path("datasets/cards/material-1-true.json") << "\"\ncushion = \""
                       << source_path("datasets/cards/material-2-true.json")
                       << "\"\n[conditions]\ntemperature_C = 60\nfriction = 0.45\n[life]\nfidelity = \"elastic\"\n";
  const auto r = run_fitcli("life --scene " + scene + " --out-dir " + out + " --plot " + out + "/life.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(out + "/life.png").substr(0, 4), "\x89PNG");
  std::vector<std::string> table;
  std::istringstream text(r.err);  // warnings on stderr
  for (std::string line; std::getline(text, line);)
    if (line.rfind("fitcli: warning: ", 0) == 0) table.push_back(line.substr(17));
  ASSERT_FALSE(table.empty()) << r.err;  // the span check's cord-line share (about 0.017 against 0.01)
  for (const char* file : {"/life.json", "/summary.json"}) {
    const auto j = nlohmann::json::parse(slurp(out + file));
    ASSERT_TRUE(j.contains("warnings")) << file;
    EXPECT_EQ(j["warnings"].get<std::vector<std::string>>(), table) << file;
  }
}
