// One command-line grammar (docs/cli.md): every subcommand's --help is walked from the top-level
// help, so a new subcommand is covered without editing this file; then the behaviour the help
// promises: "-" for stdin/stdout, one JSON document per --json run, --quiet, the card's native
// mode in eval and the conversion export uses, the data window, --version.
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/core/io.hpp"

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// Names listed under "Subcommands:" of a CLI11 help text.
std::vector<std::string> subcommands_of(const std::string& help) {
  std::vector<std::string> names;
  bool in = false;
  for (const auto& line : lines_of(help)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in = true;
    } else if (in && line.size() > 2 && line[0] == ' ' && line[2] != ' ') {
      names.push_back(line.substr(2, line.find(' ', 2) - 2));
    } else if (in && !line.empty() && line[0] != ' ') {
      in = false;
    }
  }
  return names;
}

// Long options of a help text with their description (the text up to the next option).
std::map<std::string, std::string> options_of(const std::string& help) {
  std::map<std::string, std::string> options;
  static const std::regex option_line(R"(^  (?:-[A-Za-z],)?(--[a-z0-9-]+)(.*)$)");
  std::string current;
  for (const auto& line : lines_of(help)) {
    std::smatch m;
    if (std::regex_match(line, m, option_line)) {
      current = m[1];
      options[current] += m[2].str();
    } else if (!current.empty() && line.rfind("    ", 0) == 0) {
      options[current] += " " + line;
    } else {
      current.clear();
    }
  }
  options.erase("--help");
  return options;
}

std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Every leaf subcommand ("fit", "surface fit", ...) with its help text.
std::map<std::string, std::string> leaf_helps() {
  std::map<std::string, std::string> helps;
  const auto top = run_fitcli("--help");
  EXPECT_EQ(top.exit_code, 0);
  for (const auto& name : subcommands_of(top.out)) {
    const auto r = run_fitcli(name + " --help");
    EXPECT_EQ(r.exit_code, 0) << name;
    const auto nested = subcommands_of(r.out);
    if (nested.empty()) helps[name] = r.out;
    for (const auto& sub : nested) helps[name + " " + sub] = run_fitcli(name + " " + sub + " --help").out;
  }
  return helps;
}

const std::string kShearCsv = "datasets/materials/synthetic-prony-shear.csv";
const std::string kShearCard = "datasets/cards/synthetic-prony-shear-true.json";
const std::string kWlfCsv = "datasets/materials/synthetic-prony-wlf.csv";

double value(const nlohmann::json& card, const std::string& name) {
  for (const auto& p : card["parameters"])
    if (p["name"] == name) return p["value"].get<double>();
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

}  // namespace

TEST(CliGrammar, EveryLeafHasJsonQuietVerboseAndFilesOrFolders) {
  const auto helps = leaf_helps();
  ASSERT_GE(helps.size(), 14u);  // 11 commands + surface fit, eval, grid
  for (const auto& [name, help] : helps) {
    const auto options = options_of(help);
    for (const char* common : {"--json", "--quiet", "--verbose"})
      EXPECT_TRUE(options.count(common)) << name << " lacks " << common << "\n" << help;
    for (const auto& [option, text] : options) {
      if (option == "--out") {
        EXPECT_NE(lower(text).find("file"), std::string::npos) << name << " " << option << ":" << text;
        EXPECT_EQ(lower(text).find("folder"), std::string::npos) << name << " " << option << ":" << text;
      }
      if (option == "--out-dir") {
        EXPECT_NE(lower(text).find("folder"), std::string::npos) << name << ":" << text;
      }
    }
  }
}

// Every number option of every subcommand refuses NaN and inf at the command line (exit 2, the
// option and the value named): CLI11's ranges let NaN through, and `eval --temperature-c nan`
// printed the reference temperature's moduli, `synth --noise nan` ended in exit 4.
TEST(CliGrammar, EveryNumberOptionRefusesNanAndInf) {
  int checked = 0;
  for (const auto& [name, help] : leaf_helps())
    for (const auto& [option, text] : options_of(help)) {
      if (text.find("FLOAT") == std::string::npos) continue;
      for (const char* value : {"nan", "inf", "-inf"}) {
        const auto r = run_fitcli(name + " " + option + " " + value);
        EXPECT_EQ(r.exit_code, 2) << name << " " << option << " " << value << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("fitcli: error: " + option + ": ", 0), 0u) << r.err;
        EXPECT_NE(r.err.find(std::string("got ") + value), std::string::npos) << r.err;
      }
      ++checked;
    }
  EXPECT_GE(checked, 30);
  const auto word = run_fitcli("eval --frequency-hz abc");
  EXPECT_NE(word.err.find("--frequency-hz: 'abc' is not a number"), std::string::npos) << word.err;
  const auto zero = run_fitcli("eval --frequency-hz 0");
  EXPECT_NE(zero.err.find("--frequency-hz: must be > 0, got 0"), std::string::npos) << zero.err;
}

// Number options with a meaning only in a range refuse values outside it at the command line (exit
// 2, the option named), before any work. Each of these ran without a word: `fit --max-iterations -5`
// printed Ceres's "Invalid configuration" and wrote a card, `--reference-c -400` wrote a card at
// -400 degC, `accumulate --cycles 0` a map of one cycle, `--omega-points 0` a header only,
// `waveform --frequency-hz -5` ignored it, `export --material-id -7` wrote MAT -7.
TEST(CliGrammar, OutOfRangeNumberOptionsAreRefusedNamingTheOption) {
  const std::string fit = "fit --data " + source_path(kShearCsv) + " --model prony --terms 2 --out " +
                          temp_file("range_card.json");
  const std::string card = source_path("tests/data/surface/prony_shear_card.json");
  const std::pair<std::string, std::string> cases[] = {
      {fit, "--max-terms -3"},          {fit, "--term-search-max -1"},  {fit, "--smoothness -5"},
      {fit, "--polynomial-degree 9"},   {fit, "--reference-c -400"},    {fit, "--multistart 0"},
      {fit, "--tolerance -1"},          {fit, "--max-iterations -5"},
      {"export --card " + card + " --format ansys --out " + temp_file("range.inp"), "--material-id -7"},
      {"synth --card " + card + " --frequency-hz 1 --out " + temp_file("range.csv"), "--amplitude -0.1"},
      {"accumulate --spectrum box", "--cycles 0"},         {"accumulate --spectrum box", "--omega-points 0"},
      {"accumulate --spectrum box", "--shear-stress-mpa -1"}, {"accumulate --spectrum box", "--kappa -2"},
      // 2026-11-29: a strain of 1e9 ran (stresses of 1e9 MPa); material-point's counts said "--cycles ≥ 1,
      // --steps-per-cycle ≥ 4 and --frequency > 0 are needed" whichever was wrong; --bulk-modulus -5 ran.
      {"eval --card " + card + " --frequency-hz 1", "--amplitude 1e9"},
      {"synth --card " + card + " --frequency-hz 1 --out " + temp_file("range2.csv"), "--amplitude 11"},
      {"surface grid --card " + card + " --frequency-hz 1", "--amplitude 20"},
      {"material-point --card " + card, "--amplitude 1e9"},   {"material-point --card " + card, "--mean-strain -20"},
      {"material-point --card " + card, "--frequency-hz 0"},  {"material-point --card " + card, "--cycles 0"},
      {"material-point --card " + card, "--steps-per-cycle 1"}, {"material-point --card " + card, "--bulk-modulus -5"}};
  for (const auto& [command, option] : cases) {
    const auto r = run_fitcli(command + " " + option);
    EXPECT_EQ(r.exit_code, 2) << command << " " << option << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("fitcli: error: " + option.substr(0, option.find(' ')) + ": must be", 0), 0u) << r.err;
  }
  const auto order = run_fitcli("accumulate --spectrum box --omega-min 10 --omega-max 1");
  EXPECT_EQ(order.exit_code, 2);
  EXPECT_NE(order.err.find("--omega-max 1 is below --omega-min 10"), std::string::npos) << order.err;
  const auto work = run_fitcli("accumulate --spectrum box --omega-points 100000 --cycle-points 100");
  EXPECT_EQ(work.exit_code, 2);
  EXPECT_NE(work.err.find("exceeds the work cap"), std::string::npos) << work.err;
  // waveform (given the signal file it needs): the option is refused before the file is read.
  const std::string signal = temp_file("range_signal.csv");
  std::ofstream(signal) << "time_s,stress_MPa,strain\n0,0,0\n0.1,1,0.01\n";
  const auto wave = run_fitcli("waveform --signals " + signal + " --frequency-hz -5");
  EXPECT_EQ(wave.exit_code, 2) << wave.err;
  EXPECT_NE(wave.err.find("--frequency-hz: must be > 0, got -5"), std::string::npos) << wave.err;
}

// A file handed to the wrong option is named by what it looks like (exit 3): a table as a card said
// "invalid JSON" at 1:1, a card as a scene "expected keys, tables, whitespace or comments, saw '{'".
TEST(CliGrammar, AFileOfTheWrongKindIsNamedAsSuch) {
  const std::string table = source_path(kShearCsv), card = source_path("tests/data/surface/prony_shear_card.json"),
                    scene = source_path("datasets/drives/ref-0500-light.toml");
  const std::pair<std::string, std::string> cases[] = {
      {"eval --card " + table + " --frequency-hz 1", "it looks like a CSV table, not JSON"},
      {"eval --card " + scene + " --frequency-hz 1", "it looks like a TOML file (a scene, a sweep or a schedule), not JSON"},
      {"life --scene " + card + " --out-dir " + temp_file("kind_life"), "it looks like a JSON document"},
      {"belt --scene " + table + " --out-dir " + temp_file("kind_belt"), "it looks like a CSV table, not TOML"},
      {"fit --data " + card + " --model prony --out " + temp_file("kind.json"), "it looks like a JSON document"},
      {"fit --data " + scene + " --model prony --out " + temp_file("kind.json"), "it looks like a TOML file"}};
  for (const auto& [command, hint] : cases) {
    const auto r = run_fitcli(command);
    EXPECT_EQ(r.exit_code, 3) << command << "\n" << r.err;
    EXPECT_NE(r.err.find(hint), std::string::npos) << command << "\n" << r.err;
  }
}

// A figure cannot go to stdout: every --plot (and plot's --out) refuses `-` before the work, so the
// card or folder the run would have written is not written (life-fit wrote its card, then exit 2).
TEST(CliGrammar, FiguresRefuseStdoutBeforeTheWork) {
  const std::string card = temp_file("png_dash_card.json"), dir = temp_file("png_dash_life");
  for (const std::string& args :
       {"fit --data " + source_path(kShearCsv) + " --model prony --terms 2 --out " + card + " --plot -",
        "life-fit --observed " + source_path("datasets/life-tests/synthetic-beam.csv") + " --out " + card + " --plot -",
        "life --scene " + source_path("datasets/drives/ref-0500-light.toml") + " --out-dir " + dir + " --plot -",
        "belt --scene " + source_path("datasets/drives/ref-0500-light.toml") + " --out-dir " + dir + " --plot -",
        "surface fit --data " + source_path(kShearCsv) + " --x frequency_Hz --y storage_MPa --out " + card + " --plot -",
        "eval --card " + source_path(kShearCard) + " --frequency-hz 1 --data " + source_path(kShearCsv) + " --plot -",
        "plot --card " + source_path(kShearCard) + " --data " + source_path(kShearCsv) + " --out -"}) {
    const auto r = run_fitcli(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("a PNG needs a file"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(card)) << args;
    EXPECT_FALSE(std::filesystem::exists(dir)) << args;
  }
}

TEST(CliGrammar, DocsCliNamesEverySubcommandAndOption) {
  const std::string doc = slurp(source_path("docs/cli.md"));
  ASSERT_FALSE(doc.empty());
  for (const auto& [name, help] : leaf_helps()) {
    EXPECT_NE(doc.find("fitcli " + name), std::string::npos) << "docs/cli.md does not show `fitcli " << name << "`";
    for (const auto& entry : options_of(help))
      EXPECT_NE(doc.find(entry.first), std::string::npos) << "docs/cli.md does not mention " << name << " " << entry.first;
  }
}

TEST(CliGrammar, HelpNamesOnlyDocFilesThatExist) {
  std::string all = run_fitcli("--help").out;
  for (const auto& [name, help] : leaf_helps()) all += help;
  static const std::regex doc_file(R"(([A-Za-z0-9_./-]*)\b([A-Za-z0-9_-]+\.md)\b)");
  int named = 0;
  for (std::sregex_iterator it(all.begin(), all.end(), doc_file), end; it != end; ++it) {
    const std::string path = (*it)[1].str() + (*it)[2].str();
    EXPECT_EQ(path.rfind("docs/", 0), 0u) << "'" << path << "' is not named by its repository path";
    EXPECT_FALSE(slurp(source_path(path)).empty()) << path << " does not exist";
    ++named;
  }
  EXPECT_GT(named, 0);
}

TEST(CliGrammar, ExportFormatsInHelpAreWhatExportAccepts) {
  const auto top = run_fitcli("--help").out;
  const auto help = run_fitcli("export --help").out;
  for (const auto& f : fitlib::card::export_formats()) {
    EXPECT_NE(top.find(f), std::string::npos) << f;
    const int cap = fitlib::card::max_prony_terms(f);
    if (cap > 0) {
      EXPECT_NE(help.find(f + " (at most " + std::to_string(cap)), std::string::npos) << help;
    }
  }
  EXPECT_EQ(lower(top).find("calculix"), std::string::npos) << top;
  EXPECT_EQ(run_fitcli("export --card " + source_path(kShearCard) + " --format calculix").exit_code, 2);
  // fit --max-terms names the same limits.
  EXPECT_NE(run_fitcli("fit --help").out.find("lsdyna (at most " + std::to_string(fitlib::card::max_prony_terms("lsdyna"))),
            std::string::npos);
}

TEST(CliGrammar, VersionNamesCommitAndDependencies) {
  const auto r = run_fitcli("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find(std::string("fitcli ") + FITLIB_VERSION), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("commit "), std::string::npos) << r.out;
  for (const char* dep : {"Ceres ", "NLopt ", "Eigen ", "Boost ", "toml++ ", "nlohmann-json ", "CLI11 ", "freexl "})
    EXPECT_NE(r.out.find(dep), std::string::npos) << dep << " missing: " << r.out;
}

// fit --out - | eval --card -: the card on stdout is the card a file gets, and eval reads it.
TEST(CliGrammar, DashRoundTripsThroughAPipe) {
  const std::string file = temp_file("grammar_card.json");
  const std::string fit = "fit --data " + source_path(kShearCsv) + " --model prony --terms 3 --quiet";
  ASSERT_EQ(run_fitcli(fit + " --out " + file).exit_code, 0);
  const auto piped = run_fitcli(fit + " --out -");
  ASSERT_EQ(piped.exit_code, 0) << piped.err;
  // Nothing but the card on stdout: the card the file got, but for the command it records.
  const auto without_command = [](std::string card) {
    const auto at = card.find("\"command\"");
    return at == std::string::npos ? card : card.erase(at, card.find('\n', at) - at);
  };
  EXPECT_EQ(without_command(piped.out), without_command(slurp(file)));
  const auto through = run_fitcli(fit + " --out - | " + FITCLI_EXE + " eval --card - --frequency-hz 0.5,5");
  const auto direct = run_fitcli("eval --card " + file + " --frequency-hz 0.5,5");
  ASSERT_EQ(through.exit_code, 0) << through.err;
  EXPECT_EQ(through.out, direct.out);
  EXPECT_NE(direct.out.find("shear,"), std::string::npos) << direct.out;
}

// --data - reads stdin; the card names it "stdin" with the sha256 of the bytes read.
TEST(CliGrammar, StdinDataIsNamedStdinWithItsHash) {
  const std::string card = temp_file("grammar_stdin_card.json");
  const auto r = run_fitcli("fit --data - --model prony --terms 2 --quiet --out " + card + " < " + source_path(kShearCsv));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(card));
  EXPECT_EQ(j["provenance"]["data_files"], nlohmann::json::array({"stdin"}));
  EXPECT_EQ(j["provenance"]["data_sha256"][0], fitlib::core::sha256_hex(slurp(source_path(kShearCsv))));
  const auto bad = run_fitcli("eval --card - --frequency-hz 1 < " + source_path(kShearCsv));
  EXPECT_EQ(bad.exit_code, 3);
  EXPECT_NE(bad.err.find("stdin"), std::string::npos) << bad.err;
  EXPECT_EQ(bad.err.find("fitcli-"), std::string::npos) << "scratch path leaked: " << bad.err;
}

// Every subcommand's --json prints exactly one JSON document on stdout.
TEST(CliGrammar, JsonParsesForEverySubcommand) {
  const std::string dir = temp_file("grammar_json");
  std::filesystem::create_directories(dir);
  const std::string card = dir + "/card.json", surface = dir + "/s.json";
  ASSERT_EQ(run_fitcli("fit --data " + source_path(kShearCsv) + " --model prony --terms 3 -q --out " + card).exit_code, 0);
  const std::string hyperelastic = dir + "/hyperelastic.json";
  ASSERT_EQ(run_fitcli("fit --data " + source_path("datasets/materials/treloar1944-czhao.csv") +
                       " --model yeoh -q --out " + hyperelastic).exit_code, 0);
  const std::string scene = dir + "/segment.toml";
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-light.toml"))
                       << "\n[segment]\nfine_size_mm = 1.0\ncoarse_size_mm = 2.5\ncentral_pitches = 1.0\n"
                          "end_pitches = 1.0\ncushion_rows = 1\nstrain = 0.001\n[segment.materials]\n"
                          "bottom = {E_MPa = 20, nu = 0.49}\ncushion = {E_MPa = 8, nu = 0.49}\n";
  const std::string wave = source_path("tests/data/waveforms/");
  const std::map<std::string, std::string> runs = {
      {"fit", "fit --data " + source_path(kShearCsv) + " --model prony --terms 3"},
      {"eval", "eval --card " + card + " --frequency-hz 1,10"},
      {"visco-card", "visco-card --base " + hyperelastic + " --prony " + card + " -q"},
      {"export", "export --card " + card + " --format abaqus"},
      {"synth", "synth --card " + card + " --frequency-hz 1,10 --out " + dir + "/synth.csv"},
      {"waveform", "waveform --signals " + wave + "stress_strain_harmonic_60Hz.csv " + wave + "shear_sandwich_3Hz.csv"},
      {"surface fit", "surface fit --data " + source_path("tests/data/surface/shear_3x3x3_missing.csv") +
                          " --x strain_amplitude --x frequency_Hz --x temperature_C --y storage_MPa --out " + surface},
      {"surface grid", "surface grid --card " + card + " --frequency-hz 1,10 --temperature-c 20,40"},
      {"belt", "belt --scene " + source_path("datasets/drives/ref-0500-heavy.toml") + " --out-dir " + dir + "/belt"},
      {"accumulate", "accumulate --spectrum box --cycle-points 5 --omega-points 5"},
      {"material-point", "material-point --card " + card + " --bulk-modulus 20 --cycles 1 --steps-per-cycle 8"},
      {"plot", "plot --data " + source_path(kShearCsv) + " --card " + card + " --out " + dir + "/fig.png"},
      {"segment", "segment --scene " + scene},
      {"life", "life --scene " + source_path("datasets/drives/ref-0500-heavy.toml") + " --out-dir " + dir + "/life"},
      {"sweep", "sweep --sweep " + source_path("tests/data/sweep/small.toml") + " --threads 1 -q"},
      {"life-fit", "life-fit --observed " + source_path("datasets/life-tests/synthetic-beam.csv") + " --out " + dir +
                       "/life-card.json"},
  };
  std::set<std::string> covered;
  for (const auto& [name, args] : runs) {
    const auto r = run_fitcli(args + " --json");
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    nlohmann::json j;
    EXPECT_NO_THROW(j = nlohmann::json::parse(r.out)) << name << " stdout is not one JSON document:\n" << r.out;
    covered.insert(name);
    if (name == "surface fit") {
      const auto e = run_fitcli("surface eval --surface " + surface + " --at 0.01,10,50 --json");
      EXPECT_NO_THROW(nlohmann::json::parse(e.out)) << e.out << e.err;
      covered.insert("surface eval");
    }
    if (name == "waveform") {  // several files: the records in argument order
      ASSERT_EQ(j["records"].size(), 2u) << r.out;
      EXPECT_NE(j["records"][0]["source"]["signals"].get<std::string>().find("60Hz"), std::string::npos);
    }
  }
  for (const auto& entry : leaf_helps()) EXPECT_TRUE(covered.count(entry.first)) << entry.first << " has no --json run here";
}

// --quiet: a fit with quality warnings and solver notes leaves stderr empty; without it they show.
TEST(CliGrammar, QuietLeavesStderrEmpty) {
  const std::string fit = "fit --data " + source_path(kWlfCsv) + " --model prony --terms 3 --temperature-law wlf";
  const auto loud = run_fitcli(fit);
  ASSERT_EQ(loud.exit_code, 0);
  EXPECT_NE(loud.err.find("fitcli: warning:"), std::string::npos) << loud.err;
  EXPECT_NE(loud.err.find("fitcli: note:"), std::string::npos) << loud.err;
  EXPECT_EQ(loud.out.find("note:"), std::string::npos) << "notes belong on stderr";
  const auto quiet = run_fitcli(fit + " --quiet");
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_EQ(quiet.err, "");
  EXPECT_NE(quiet.out.find("verdict:"), std::string::npos) << "results stay on stdout";
}

// eval takes the card's own mode; --mode uniaxial of a shear card converts as export does:
// K = 2G0(1 + nu)/(3(1 - 2nu)) from the instantaneous G0, E* = 9KG*/(3K + G*).
TEST(CliGrammar, EvalNativeModeAndExportsConversion) {
  const auto card = nlohmann::json::parse(slurp(source_path(kShearCard)));
  const double nu = 0.45;
  double G0 = value(card, "G_inf");
  for (int i = 1; i <= card["options"]["terms"].get<int>(); ++i) G0 += value(card, "G_" + std::to_string(i));
  const double K = 2.0 * G0 * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu));
  const auto shear = run_fitcli("eval --card " + source_path(kShearCard) + " --frequency-hz 2 --json");
  const auto uni = run_fitcli("eval --card " + source_path(kShearCard) +
                              " --frequency-hz 2 --mode uniaxial --poisson-ratio 0.45 --json");
  ASSERT_EQ(shear.exit_code, 0) << shear.err;
  ASSERT_EQ(uni.exit_code, 0) << uni.err;
  const auto s = nlohmann::json::parse(shear.out), u = nlohmann::json::parse(uni.out);
  EXPECT_EQ(s["mode"], "shear");
  const std::complex<double> G(s["rows"][0]["storage_MPa"].get<double>(), s["rows"][0]["loss_MPa"].get<double>());
  const std::complex<double> E = 9.0 * K * G / (3.0 * K + G);
  EXPECT_NEAR(u["rows"][0]["storage_MPa"].get<double>(), E.real(), 1e-12 * E.real());
  EXPECT_NEAR(u["rows"][0]["loss_MPa"].get<double>(), E.imag(), 1e-12 * E.real());
  // The Abaqus export of the same card states the same instantaneous E0 = 9KG0/(3K + G0).
  const auto deck = run_fitcli("export --card " + source_path(kShearCard) + " --format abaqus --poisson-ratio 0.45");
  ASSERT_EQ(deck.exit_code, 0) << deck.err;
  const double E0 = 9.0 * K * G0 / (3.0 * K + G0);
  const auto at = deck.out.find("MODULI=INSTANTANEOUS\n");
  ASSERT_NE(at, std::string::npos) << deck.out;
  EXPECT_NEAR(std::stod(deck.out.substr(at + 21)), E0, 1e-8 * E0);
}

// A uniaxial card (pyvisco) evaluates without --mode; shear keeps nu constant: G* = E*/(2(1 + nu)).
TEST(CliGrammar, EvalUniaxialCardWithoutMode) {
  const std::string card = temp_file("grammar_uniaxial.json");
  ASSERT_EQ(run_fitcli("fit --data " + source_path("datasets/materials/pyvisco-freq-master.csv") +
                       " --format pyvisco --model prony --terms 4 -q --out " + card).exit_code, 0);
  const auto e = run_fitcli("eval --card " + card + " --frequency-hz 3 --json");
  ASSERT_EQ(e.exit_code, 0) << e.err;
  const auto g = run_fitcli("eval --card " + card + " --frequency-hz 3 --mode shear --poisson-ratio 0.4 --json");
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const auto E = nlohmann::json::parse(e.out), G = nlohmann::json::parse(g.out);
  EXPECT_EQ(E["mode"], "uniaxial");
  EXPECT_NEAR(G["rows"][0]["storage_MPa"].get<double>(), E["rows"][0]["storage_MPa"].get<double>() / 2.8,
              1e-12 * E["rows"][0]["storage_MPa"].get<double>());
}

// Beyond the data window (23..60 degC here): exit 3 naming the window and the option; with
// --allow-extrapolation a warning and "extrapolated": true.
TEST(CliGrammar, EvalRefusesOrFlagsExtrapolation) {
  const std::string card = temp_file("grammar_window.json");
  ASSERT_EQ(run_fitcli("fit --data " + source_path(kWlfCsv) + " --model prony --terms 3 --temperature-law wlf -q --out " +
                       card).exit_code, 0);
  const auto window = nlohmann::json::parse(slurp(card))["fit"]["data_window"];
  EXPECT_EQ(window["temperature_C"], nlohmann::json::array({-20.0, 80.0}));
  const auto refused = run_fitcli("eval --card " + card + " --frequency-hz 1 --temperature-c 300");
  EXPECT_EQ(refused.exit_code, 3);
  EXPECT_NE(refused.err.find("[-20, 80]"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--allow-extrapolation"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.out, "");
  const auto flagged = run_fitcli("eval --card " + card + " --frequency-hz 1 --temperature-c 23,300 --allow-extrapolation --json");
  ASSERT_EQ(flagged.exit_code, 0) << flagged.err;
  const auto rows = nlohmann::json::parse(flagged.out)["rows"];
  EXPECT_EQ(rows[0]["extrapolated"], false);
  EXPECT_EQ(rows[1]["extrapolated"], true);
  EXPECT_NE(flagged.err.find("fitcli: warning: extrapolating"), std::string::npos) << flagged.err;
}

// Deprecated spellings still work for one release, each with a note naming the new one.
TEST(CliGrammar, DeprecatedAliasesNoteTheirReplacement) {
  const std::string dir = temp_file("grammar_belt_old");
  const auto belt = run_fitcli("belt --scene " + source_path("tests/data/scenes/minimal.toml") + " --out " + dir);
  EXPECT_EQ(belt.exit_code, 0) << belt.err;
  EXPECT_NE(belt.err.find("--out-dir"), std::string::npos) << belt.err;
  EXPECT_FALSE(slurp(dir + "/summary.json").empty());
  // ... but not a name with an extension: --out names a file elsewhere, and belt would make a
  // folder called lh.csv.
  const std::string file_like = temp_file("grammar_belt_lh.csv");
  const auto as_file = run_fitcli("belt --scene " + source_path("tests/data/scenes/minimal.toml") + " --out " + file_like);
  EXPECT_EQ(as_file.exit_code, 2) << as_file.err;
  EXPECT_NE(as_file.err.find("belt writes a folder"), std::string::npos) << as_file.err;
  EXPECT_FALSE(std::filesystem::exists(file_like));
  const auto synth = run_fitcli("synth --card " + source_path(kShearCard) + " --frequency-hz 1 --material old --out " +
                                temp_file("grammar_synth.csv"));
  EXPECT_EQ(synth.exit_code, 0) << synth.err;
  EXPECT_NE(synth.err.find("--name"), std::string::npos) << synth.err;
  EXPECT_NE(slurp(temp_file("grammar_synth.csv")).find(",old,"), std::string::npos);
}

// waveform takes many files: one row per file in argument order, each naming its file.
TEST(CliGrammar, WaveformManyFilesOneTable) {
  const std::string a = source_path("tests/data/waveforms/stress_strain_harmonic_60Hz.csv");
  const std::string b = source_path("tests/data/waveforms/shear_sandwich_3Hz.csv");
  const std::string table = temp_file("grammar_waves.csv");
  const auto r = run_fitcli("waveform --signals " + b + " " + a + " --out " + table);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto text = slurp(table);
  // Rows in argument order: the 3 Hz shear sandwich (labelled S1 by its metadata), then the
  // 60 Hz uniaxial record, which has no label and is labelled with its file.
  const auto shear = text.find("\nshear,12,3,"), uniaxial = text.find("\nuniaxial,,");
  ASSERT_NE(shear, std::string::npos) << text;
  ASSERT_NE(uniaxial, std::string::npos) << text;
  EXPECT_LT(shear, uniaxial);
  EXPECT_NE(text.find(",S1,"), std::string::npos) << text;
  EXPECT_NE(text.find("," + a + ","), std::string::npos) << text;
}

// fit --plot writes the figure fitcli plot makes of the same data and card, after the card.
TEST(CliGrammar, FitPlotIsThePlotFigure) {
  const std::string card = temp_file("grammar_plot_card.json"), a = temp_file("grammar_fit.png"),
                    b = temp_file("grammar_plot.png");
  const auto fit = run_fitcli("fit --data " + source_path(kShearCsv) + " --model prony --terms 3 -q --out " + card +
                              " --plot " + a);
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  ASSERT_EQ(run_fitcli("plot --data " + source_path(kShearCsv) + " --card " + card + " --out " + b).exit_code, 0);
  const std::string png = slurp(a);
  EXPECT_EQ(png.substr(0, 4), "\x89PNG");
  EXPECT_EQ(png, slurp(b));
  const std::string c = temp_file("grammar_eval.png");
  const auto eval = run_fitcli("eval --card " + card + " --frequency-hz 1 --plot " + c + " --data " + source_path(kShearCsv));
  ASSERT_EQ(eval.exit_code, 0) << eval.err;
  EXPECT_EQ(slurp(c), png);
  // A user's name with a quote and gnuplot's markup characters is drawn, not parsed.
  const auto quoted = run_fitcli("fit --data " + source_path(kShearCsv) + " --model prony --terms 3 -q --out " + card +
                                 " --name \"Bob's rubber_{2}^x\" --plot " + a);
  ASSERT_EQ(quoted.exit_code, 0) << quoted.err;
  EXPECT_EQ(slurp(a).substr(0, 4), "\x89PNG");
}
