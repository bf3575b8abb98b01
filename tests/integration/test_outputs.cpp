// Outputs that never lie or get lost (docs/reliability.md "Outputs"): a failed write of stdout is
// an error (exit 3), an output that is an input or another output is refused before any work
// (exit 2), a sweep's output is locked, and each row a sweep resumes is verified.
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/scene/sweep.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kCard = source_path("tests/data/bad/card/ok.json");
const std::string kTable = source_path("datasets/materials/synthetic-prony-shear.csv");
const std::string kSweep = source_path("tests/data/sweep/small.toml");

std::string copy_of(const std::string& from, const std::string& name) {
  const std::string to = temp_file(name);
  fs::copy_file(from, to, fs::copy_options::overwrite_existing);
  return to;
}

// run_fitcli appends its own redirections; these run the shell line themselves.
int exit_of(const std::string& line) {
  const int status = std::system(line.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(Outputs, StdoutThatCannotBeWrittenExitsThree) {
  const std::string err = temp_file("stdout_full.err");
  const std::string fitcli = FITCLI_EXE;
  for (const std::string args : {"eval --card " + kCard + " --frequency-hz 1,2,3",
                                 "eval --card " + kCard + " --time-s 1,2 --json",
                                 "export --card " + kCard + " --format abaqus",
                                 "material-point --card " + kCard + " --cycles 1 --steps-per-cycle 20",
                                 "sweep --sweep " + kSweep + " --threads 1 --quiet"}) {
    EXPECT_EQ(exit_of(fitcli + " " + args + " >/dev/full 2>" + err), 3) << args;
    EXPECT_NE(slurp(err).find("stdout: cannot write the output"), std::string::npos) << slurp(err);
    EXPECT_EQ(exit_of(fitcli + " " + args + " >&- 2>" + err), 3) << args;  // a closed stdout
    EXPECT_NE(slurp(err).find("stdout: cannot write the output (stdout is closed)"), std::string::npos) << slurp(err);
  }
  // A closed stdout no longer lends fd 1 to the card being written: the card is the card.
  const std::string card = temp_file("closed_stdout_card.json");
  EXPECT_EQ(exit_of(fitcli + " fit --data " + kTable + " --model prony --terms 2 --out " + card + " --quiet >&- 2>" + err), 3);
  EXPECT_EQ(slurp(card).rfind("{", 0), 0u) << slurp(card).substr(0, 200);
  // Nothing on stdout: a closed stdout is no error.
  EXPECT_EQ(exit_of(fitcli + " export --card " + kCard + " --format abaqus --out " + temp_file("m.inp") + " >&- 2>" + err), 0)
      << slurp(err);
}

TEST(Outputs, AnOutputThatIsAnInputIsRefusedBeforeAnyWork) {
  const std::string table = copy_of(kTable, "collide_table.csv"), card = copy_of(kCard, "collide_card.json");
  const std::string sweep = temp_file("collide_sweep.toml");
  const std::string table_bytes = slurp(table), card_bytes = slurp(card);
  fs::create_symlink(card, temp_file("card_link.json"));
  fs::create_hard_link(table, temp_file("table_hard.csv"));
  const std::string dir = fs::path(table).parent_path().string();
  struct Case {
    std::string args, message;
  };
  for (const Case& c : std::initializer_list<Case>{
           {"fit --data " + table + " --model prony --terms 2 --out " + table, "--out " + table + " is the file --data reads"},
           {"fit --data " + table + " --model prony --terms 2 --out " + dir + "/./collide_table.csv", "--data reads"},
           {"fit --data " + table + " --model prony --terms 2 --out " + temp_file("table_hard.csv"), "--data reads"},
           {"eval --card " + card + " --frequency-hz 1 --out " + card, "--card reads"},
           {"eval --card " + temp_file("card_link.json") + " --frequency-hz 1 --out " + card, "--card reads"},
           {"export --card " + card + " --format abaqus --out " + card, "--card reads"},
           {"fit --data " + table + " --model prony --terms 2 --out " + temp_file("c.json") + " --plot " +
                temp_file("c.json"), "--plot and --out name one file"},
           {"life-fit --observed " + source_path("datasets/life-tests/synthetic-beam.csv") + " --out " +
                temp_file("lf.json") + " --peaks-out " + temp_file("lf.json"), "--peaks-out and --out name one file"},
       }) {
    const auto r = run_fitcli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
  EXPECT_EQ(slurp(table), table_bytes);
  EXPECT_EQ(slurp(card), card_bytes);
  EXPECT_FALSE(fs::exists(temp_file("c.json")));
  EXPECT_FALSE(fs::exists(temp_file("lf.json")));
}

std::string cut_checksums(const std::string& partial) {  // FILE.partial without its row_sha256 column
  std::string out;
  std::istringstream in(partial);
  for (std::string line; std::getline(in, line);) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

TEST(Outputs, ADamagedResumedRowIsRefusedAtItsLine) {
  const std::string whole = temp_file("sweep_whole.csv"), out = temp_file("sweep_damaged.csv");
  ASSERT_EQ(run_fitcli("sweep --sweep " + kSweep + " --out " + whole + " --threads 1 --quiet").exit_code, 0);
  ASSERT_EQ(run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 1 --quiet --stop-after 9").exit_code, 0);
  const std::string partial = slurp(out + ".partial");
  EXPECT_EQ(slurp(whole).compare(0, cut_checksums(partial).size(), cut_checksums(partial)), 0);
  // Row of case 4 (line 7): one digit of a number changed, then a nan.
  auto line_start = [&](int line) {
    std::size_t at = 0;
    for (int k = 1; k < line; ++k) at = partial.find('\n', at) + 1;
    return at;
  };
  const std::size_t row = line_start(7), digit = partial.find_first_of("123456789", partial.find(",", row + 2));
  std::string changed = partial;
  changed[digit] = changed[digit] == '9' ? '8' : static_cast<char>(changed[digit] + 1);
  std::ofstream(out + ".partial", std::ios::binary | std::ios::trunc) << changed;
  auto r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find(out + ".partial:7:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("row_sha256"), std::string::npos) << r.err;
  std::string with_nan = partial;
  with_nan.replace(digit, 1, "nan");
  std::ofstream(out + ".partial", std::ios::binary | std::ios::trunc) << with_nan;
  r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find(out + ".partial:7:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  // The intact partial resumes to the bytes of an uninterrupted run.
  std::ofstream(out + ".partial", std::ios::binary | std::ios::trunc) << partial;
  r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(out), slurp(whole));
  EXPECT_FALSE(fs::exists(out + ".partial"));
  EXPECT_FALSE(fs::exists(out + ".lock"));
}

TEST(Outputs, TwoSweepsOnOneOutputTheSecondIsRefused) {
  const std::string out = temp_file("sweep_locked.csv");
  const int fd = ::open((out + ".lock").c_str(), O_RDWR | O_CREAT, 0644);  // as a running sweep holds it
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const auto r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find(out + ": another run is writing this output now"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("filesystem error"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out + ".partial"));
  ::close(fd);  // the holder is gone: its leftover lock file blocks nothing
  const auto again = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 1 --quiet");
  EXPECT_EQ(again.exit_code, 0) << again.err;
  EXPECT_TRUE(fs::exists(out));
}

// A card that a sweep's scene names (not an axis) is one of its inputs too: changed between a stop
// and the resume, the unfinished file is refused (its rows were computed with the old card); and
// the result file may not replace it.
TEST(Outputs, ASweepResumeRefusesRowsOfACardItsSceneNamesThatChanged) {
  const std::string card = copy_of(source_path("datasets/cards/material-1-true.json"), "scene_card.json");
  const std::string scene = temp_file("scene_with_card.toml"), sweep = temp_file("sweep_scene_card.toml");
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-medium.toml"))
                       << "\n[belt.materials]\nbottom = \"scene_card.json\"\n";
  std::ofstream(sweep) << "scenes = [\"scene_with_card.toml\"]\n[set]\n\"life.fidelity\" = \"beam\"\n"
                       << "[[axis]]\nkey = \"drive.torque_Nm\"\nvalues = [5, 10, 15, 20]\n"
                       << "[outputs]\ncolumns = [\"life_h\"]\n";
  const std::string out = temp_file("sweep_scene_card.csv");
  ASSERT_EQ(run_fitcli("sweep --sweep " + sweep + " --out " + out + " --threads 1 --quiet --stop-after 2").exit_code, 0);
  ASSERT_TRUE(fs::exists(out + ".partial"));
  fs::copy_file(source_path("datasets/cards/material-2-true.json"), card, fs::copy_options::overwrite_existing);
  auto r = run_fitcli("sweep --sweep " + sweep + " --out " + out + " --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find(out + ".partial:1:1"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("other input files"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
  const std::string card_bytes = slurp(card);
  r = run_fitcli("sweep --sweep " + sweep + " --out " + card + " --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("which the sweep reads"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(card), card_bytes);
  EXPECT_FALSE(fs::exists(card + ".partial"));
}

// The cards a scene names are inputs too: a figure, VTK or table written over one is refused
// before any work (`life --scene s.toml --plot card.json` replaced the bottom card with the PNG).
TEST(Outputs, AnOutputOnACardTheSceneNamesIsRefusedBeforeAnyWork) {
  const std::string card = copy_of(source_path("datasets/cards/material-2-true.json"), "named_card.json");
  const std::string fatigue = copy_of(source_path("datasets/cards/fatigue-fritzson-1988.json"), "named_fatigue.json");
  const std::string scene = temp_file("scene_names_cards.toml"), segment = temp_file("segment_names_cards.toml");
  const std::string cards = "\n[belt.materials]\nbottom = \"named_card.json\"\n";
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-heavy.toml")) << cards
                       << "\n[life]\ncard = \"named_fatigue.json\"\n";
  std::string segment_text = slurp(source_path("tests/data/bad/scene/life_segment_ok.toml"));
  const std::string own_bottom = "bottom = {E_MPa = 20, nu = 0.49}\n";  // the segment reads the card instead
  ASSERT_NE(segment_text.find(own_bottom), std::string::npos);
  segment_text.erase(segment_text.find(own_bottom), own_bottom.size());
  std::ofstream(segment) << segment_text << cards;
  const std::string card_bytes = slurp(card), fatigue_bytes = slurp(fatigue);
  struct Case {
    std::string args, message;
  };
  for (const Case& c : std::initializer_list<Case>{
           {"belt --scene " + scene + " --out-dir " + temp_file("b") + " --plot " + card, "belt.materials.bottom"},
           {"life --scene " + scene + " --out-dir " + temp_file("l") + " --plot " + card, "belt.materials.bottom"},
           {"life --scene " + scene + " --out-dir " + temp_file("l") + " --plot " + fatigue, "life.card"},
           {"segment --scene " + segment + " --vtk " + card, "belt.materials.bottom"},
           {"accumulate --scene " + scene + " --out " + card, "belt.materials.bottom"},
       }) {
    const auto r = run_fitcli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find("is the card the scene names at " + c.message), std::string::npos) << r.err;
  }
  EXPECT_EQ(slurp(card), card_bytes);
  EXPECT_EQ(slurp(fatigue), fatigue_bytes);
  EXPECT_FALSE(fs::exists(temp_file("b")));
  EXPECT_FALSE(fs::exists(temp_file("l")));
}

// belt and life write several files into --out-dir (load_history.csv, summary.json, life.json, …):
// each is an output like --out. A card the scene names, the scene file or the fatigue card lying at
// one of those names (by any spelling of the folder: "/./", a symbolic link; or a hard link of the
// file) was replaced by the run's table with exit 0; a --plot on one of them lost one of the two.
// Now exit 2 before any work, naming the file and where it is read; the inputs stay as they were.
TEST(Outputs, AnOutDirWhoseFilesAreInputsIsRefusedBeforeAnyWork) {
  const std::string heavy = slurp(source_path("datasets/drives/ref-0500-heavy.toml"));
  const auto folder = [](const std::string& name) {
    const std::string d = temp_file(name);
    fs::create_directories(d);
    return d;
  };
  // A card at DIR/summary.json, a fatigue card at DIR/life.json, the scene outside DIR.
  const std::string cards = folder("outdir_cards");
  const std::string card = cards + "/summary.json", fatigue = cards + "/life.json";
  fs::copy_file(source_path("datasets/cards/material-2-true.json"), card);
  fs::copy_file(source_path("datasets/cards/fatigue-fritzson-1988.json"), fatigue);
  const std::string scene = temp_file("outdir_scene.toml");
  std::ofstream(scene) << heavy << "\n[belt.materials]\nbottom = \"outdir_cards/summary.json\"\n";
  const std::string life_scene = temp_file("outdir_life_scene.toml");
  std::ofstream(life_scene) << heavy << "\n[life]\ncard = \"outdir_cards/life.json\"\n";
  fs::create_directory_symlink(cards, temp_file("outdir_cards_link"));
  // The scene file itself at DIR/load_history.csv, and a hard link of it at DIR2/summary.json.
  const std::string own = folder("outdir_own"), linked = folder("outdir_linked");
  const std::string own_scene = own + "/load_history.csv";
  std::ofstream(own_scene) << heavy;
  fs::create_hard_link(own_scene, linked + "/summary.json");
  // A scene whose --field-at files land on its own name (DIR/field-0.vtk).
  const std::string fields = folder("outdir_fields");
  fs::copy_file(source_path("tests/data/bad/scene/life_segment_ok.toml"), fields + "/field-0.vtk");
  const std::string empty = temp_file("outdir_empty");  // not made: nothing lies there
  const std::string not_folder = copy_of(kCard, "outdir_is_a_file");
  std::map<std::string, std::string> before;
  for (const std::string& f : {card, fatigue, own_scene, fields + "/field-0.vtk"}) before[f] = slurp(f);
  struct Case {
    std::string args, message;
    int exit_code = 2;
  };
  for (const Case& c : std::initializer_list<Case>{
           {"belt --scene " + scene + " --out-dir " + cards, "summary.json is the card the scene names at belt.materials.bottom"},
           {"life --scene " + scene + " --out-dir " + cards + "/.", "is the card the scene names at belt.materials.bottom"},
           {"life --scene " + scene + " --out-dir " + temp_file("outdir_cards_link"), "belt.materials.bottom"},
           {"life --scene " + life_scene + " --out-dir " + cards, "life.json is the card the scene names at life.card"},
           {"belt --scene " + own_scene + " --out-dir " + own, "load_history.csv is the scene file the run reads"},
           {"life --scene " + own_scene + " --out-dir " + linked, "summary.json is the scene file the run reads"},
           {"life --scene " + fields + "/field-0.vtk --field-at entrance --out-dir " + fields, "field-0.vtk is the scene file"},
           {"belt --scene " + scene + " --out-dir " + scene, "--out-dir " + scene + " is the scene file the run reads"},
           {"life --scene " + source_path("datasets/drives/ref-0500-heavy.toml") + " --out-dir " + empty + " --plot " +
                empty + "/life.json", "is the file life.json that --out-dir " + empty + " receives"},
           {"belt --scene " + source_path("datasets/drives/ref-0500-heavy.toml") + " --out-dir " + empty + " --plot " +
                empty + "/./summary.json", "is the file summary.json that --out-dir"},
           {"life --scene " + source_path("datasets/drives/ref-0500-heavy.toml") + " --out-dir " + not_folder,
            "output folder is a file, not a folder", 3},
           {"life --scene " + source_path("datasets/drives/ref-0500-heavy.toml") + " --out-dir " + not_folder + "/sub",
            "cannot create output folder", 3},
       }) {
    const auto r = run_fitcli(c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
  }
  for (const auto& [path, bytes] : before) EXPECT_EQ(slurp(path), bytes) << path;
  for (const std::string& d : {cards, own, linked, fields}) {
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(d)) ++files;
    EXPECT_EQ(files, d == cards ? 2u : 1u) << d << ": the refused run wrote into it";
  }
  EXPECT_FALSE(fs::exists(empty));
  EXPECT_EQ(slurp(not_folder), slurp(kCard));
}

// A sweep writes FILE.partial and FILE.lock beside --out FILE (and removes the lock when done): a
// sweep file at either name was appended to, or deleted with the lock.
TEST(Outputs, ASweepFileAtItsOutputsPartialOrLockIsRefused) {
  for (const std::string suffix : {".partial", ".lock"}) {
    const std::string out = temp_file("sweep_own" + suffix.substr(1) + ".csv");
    const std::string sweep = copy_of(kSweep, "sweep_own" + suffix.substr(1) + ".csv" + suffix);
    const std::string text = slurp(kSweep);
    const auto r = run_fitcli("sweep --sweep " + sweep + " --out " + out + " --threads 1 --quiet");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--out's file " + out + suffix + " is the file --sweep reads"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(sweep), text);
    EXPECT_FALSE(fs::exists(out));
  }
}

// 10^6 cases at the beam level (0.675 ms each: 0.19 core-hours) run; the same grid at the elastic
// level (1 s each: about 280 core-hours) is refused with its estimate before any case runs.
TEST(Outputs, SweepWorkCapCountsCostNotCases) {
  auto values = [](double first, double step) {
    std::string v;
    for (int i = 0; i < 100; ++i) v += (i ? ", " : "") + std::to_string(first + i * step);
    return "[" + v + "]";
  };
  const std::string path = temp_file("beam_million.toml");
  std::ofstream(path) << "scenes = [\"" << source_path("datasets/drives/ref-0500-medium.toml") << "\"]\n"
                      << "[set]\n\"life.fidelity\" = \"beam\"\n"
                      << "[[axis]]\nkey = \"drive.torque_Nm\"\nvalues = " << values(5, 0.1) << "\n"
                      << "[[axis]]\nkey = \"conditions.temperature_C\"\nvalues = " << values(20, 1) << "\n"
                      << "[[axis]]\nkey = \"conditions.friction\"\nvalues = " << values(0.3, 0.002) << "\n"
                      << "[outputs]\ncolumns = [\"life_h\"]\n";
  const auto beam = fitlib::scene::load_sweep(path);
  EXPECT_EQ(beam.case_count, 1000000u);
  EXPECT_NEAR(fitlib::scene::sweep_cost_core_hours(beam), 1e6 * 0.675e-3 / 3600, 1e-9);
  try {
    fitlib::scene::load_sweep(source_path("tests/data/bad/sweep/elastic_million.toml"));
    ADD_FAILURE() << "an elastic 10^6-case sweep was accepted";
  } catch (const fitlib::core::InputError& e) {
    EXPECT_EQ(e.key(), "life.fidelity");
    EXPECT_NE(std::string(e.what()).find("about 278 core-hours"), std::string::npos) << e.what();
  }
}

// life-fit's outputs against the files its life tests read: each test's scene and the cards that
// scene names (here its [life] card) — refused before any scene runs, the files unchanged.
TEST(Outputs, LifeFitRefusesAnOutputOnATestsSceneOrItsCard) {
  const std::string fatigue = copy_of(source_path("datasets/cards/fatigue-fritzson-1988.json"), "lf_fatigue.json");
  const std::string scene = temp_file("lf_scene.toml");
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-medium.toml")) << "\n[life]\nfidelity = \"beam\"\ncard = \""
                       << fs::path(fatigue).filename().string() << "\"\n";
  const std::string tests = temp_file("lf_tests.csv");
  std::ofstream(tests) << "case,scene,failure_mode,observed_h\nA," << fs::path(scene).filename().string()
                       << ",separation,20\n";
  const std::string scene_bytes = slurp(scene), fatigue_bytes = slurp(fatigue);
  for (const std::string& out : {scene, fatigue}) {
    const auto r = run_fitcli("life-fit --observed " + tests + " --out " + out);
    EXPECT_EQ(r.exit_code, 2) << out << "\n" << r.err;
    EXPECT_NE(r.err.find(out), std::string::npos) << r.err;
    const auto p = run_fitcli("life-fit --observed " + tests + " --out " + temp_file("lf_ok.json") + " --peaks-out " + out);
    EXPECT_EQ(p.exit_code, 2) << out << "\n" << p.err;
  }
  EXPECT_EQ(slurp(scene), scene_bytes);
  EXPECT_EQ(slurp(fatigue), fatigue_bytes);
  EXPECT_FALSE(fs::exists(temp_file("lf_ok.json")));
}

}  // namespace

// An --out that is a device or FIFO (issue 37 audit: `--out /dev/full` exited 0, and as root the
// rename replaced /dev/full and the /dev/stdout link by regular files). A FIFO in the test's own
// folder stands in for the device: eval writes into it and it stays a FIFO; a sweep refuses it
// (its .partial and .lock would be made beside it), exit 3 naming the file, before any case.
TEST(Outputs, AnOutputThatIsAFifoIsWrittenInPlaceOrRefusedNeverReplaced) {
  const std::string fifo = temp_file("out.fifo");
  std::filesystem::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string bytes = temp_file("fifo_bytes.csv");
  // fitcli in the background, a reader on the FIFO as another program would be; fitcli's status.
  const std::string cmd = std::string(FITCLI_EXE) + " eval --card " + kCard + " --frequency-hz 1,10 --out " + fifo +
                          " & cat " + fifo + " > " + bytes + "; wait $!";
  const int status = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  const std::string got = slurp(bytes);
  EXPECT_NE(got.find("frequency_Hz"), std::string::npos) << got;
  EXPECT_TRUE(std::filesystem::is_fifo(std::filesystem::symlink_status(fifo)));
  const auto r = run_fitcli("sweep --sweep " + kSweep + " --out " + fifo + " --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find(fifo + ": the result file must be a regular file"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(fifo + ".partial"));
  EXPECT_TRUE(std::filesystem::is_fifo(std::filesystem::symlink_status(fifo)));
}

// An --out that is a symbolic link to a regular file (issue 37): the rename replaced the link by a
// regular file and left its target stale. Every subcommand writes through core's writer, so the
// target gets the new bytes and the link stays a link; a link naming an input is still refused.
TEST(Outputs, AnOutputThatIsALinkWritesItsTargetAndStaysALink) {
  const std::string target = temp_file("link_target.csv"), link = temp_file("out_link.csv");
  { std::ofstream(target) << "old bytes\n"; }
  fs::create_symlink("link_target.csv", link);  // relative, as `ln -s` makes them
  auto r = run_fitcli("eval --card " + kCard + " --frequency-hz 1,10 --out " + link + " --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_NE(slurp(target).find("frequency_Hz"), std::string::npos) << slurp(target);
  // A sweep too: its table replaces the target, its .partial and .lock (beside the target) are gone.
  r = run_fitcli("sweep --sweep " + kSweep + " --out " + link + " --threads 1 --quiet");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(slurp(target).rfind("# fitlib sweep sha256=", 0), 0u) << slurp(target).substr(0, 200);
  for (const char* suffix : {".partial", ".lock"})
    EXPECT_FALSE(fs::exists(target + suffix) || fs::exists(fs::symlink_status(link + suffix))) << suffix;
  const std::string card = copy_of(kCard, "linked_input_card.json"), card_link = temp_file("to_input.json");
  fs::create_symlink(card, card_link);
  r = run_fitcli("eval --card " + card + " --frequency-hz 1 --out " + card_link);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--out " + card_link + " is the file --card reads"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(card), slurp(kCard));
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(card_link)));
  // Two outputs through a dangling link and its target are one file too.
  const std::string dangling = temp_file("dangling.json");
  fs::create_symlink("lf_made.json", dangling);
  r = run_fitcli("life-fit --observed " + source_path("datasets/life-tests/synthetic-beam.csv") + " --out " + dangling +
                 " --peaks-out " + temp_file("lf_made.json"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("name one file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(temp_file("lf_made.json")));
}

// An empty output path (issue 37): `--out ''` (an unset shell variable) wrote to stdout as if --out
// were not given. Every option that names a file or folder refuses it: exit 2 naming the option,
// before any work (nothing on stdout, no file made). (`--out=` is CLI11's "1 required TEXT missing".)
TEST(Outputs, AnEmptyOutputPathIsRefusedNamingTheOption) {
  const std::string scene = source_path("datasets/drives/ref-0500-light.toml");
  const std::string observed = source_path("datasets/life-tests/synthetic-beam.csv");
  const std::string fit = "fit --data " + kTable + " --model prony --terms 2 ";
  struct Case {
    std::string args, option;
  };
  for (const Case& c : std::initializer_list<Case>{
           {"eval --card " + kCard + " --frequency-hz 1 --out ''", "--out"},
           {"export --card " + kCard + " --format abaqus --out ''", "--out"},
           {fit + "--out ''", "--out"},
           {fit + "--out " + temp_file("empty_plot.json") + " --plot ''", "--plot"},
           {fit + "--out " + temp_file("empty_shifts.json") + " --shifts-out ''", "--shifts-out"},
           {"surface grid --card " + kCard + " --frequency-hz 1,10 --surface-out ''", "--surface-out"},
           {"life-fit --observed " + observed + " --out " + temp_file("empty_lf.json") + " --peaks-out ''", "--peaks-out"},
           {"segment --scene " + source_path("datasets/segment/bend-40mm.toml") + " --vtk ''", "--vtk"},
           {"belt --scene " + scene + " --out-dir ''", "--out-dir"},
           {"sweep --sweep " + kSweep + " --out '' --threads 1", "--out"},
           {"eval --card '' --frequency-hz 1", "--card"},
       }) {
    const auto r = run_fitcli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.option + " '': an empty path names nothing"), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << c.args;
  }
  for (const char* made : {"empty_plot.json", "empty_shifts.json", "empty_lf.json"})
    EXPECT_FALSE(fs::exists(temp_file(made))) << made;
}
