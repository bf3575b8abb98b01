// A figure gnuplot cannot draw is exit 5 (README "Exit codes", docs/decisions.md "fitcli: a figure
// gnuplot cannot draw is exit 5"): no gnuplot on PATH is refused before any work, gnuplot failing
// while it draws leaves the run's other outputs standing. And one input file given twice to one
// option is refused (docs/decisions.md "fitcli: an input file given twice to one option is
// refused").
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.hpp"
#include "fitlib/card/card.hpp"

namespace {

namespace fs = std::filesystem;

const std::string kTable = source_path("datasets/materials/synthetic-prony-shear.csv");
const std::string kCard = source_path("datasets/cards/synthetic-prony-shear-true.json");

// Runs `fitcli ARGS` with PATH set to `path`; exit code, stdout and stderr.
CliResult run_with_path(const std::string& path, const std::string& args, const std::string& name) {
  const std::string out = temp_file(name + ".out"), err = temp_file(name + ".err");
  const std::string line = "PATH=" + path + " " + FITCLI_EXE + " " + args + " >" + out + " 2>" + err;
  const int status = std::system(line.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status), slurp(out), slurp(err)};
}

// A folder holding a `gnuplot` that reads its script and fails, as a broken installation would.
std::string failing_gnuplot_dir() {
  const std::string dir = temp_file("failing-gnuplot");
  fs::create_directories(dir);
  std::ofstream(dir + "/gnuplot") << "#!/bin/sh\ncat >/dev/null\necho 'gnuplot: cannot open display' >&2\nexit 1\n";
  fs::permissions(dir + "/gnuplot", fs::perms::owner_all);
  return dir;
}

std::size_t files_in(const std::string& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(Figures, NoGnuplotOnPathIsRefusedBeforeAnyWorkAndNothingIsWritten) {
  const std::string dir = temp_file("no-gnuplot");
  fs::create_directories(dir);
  const std::string empty = temp_file("no-gnuplot-path");  // a PATH folder without gnuplot
  fs::create_directories(empty);
  for (const std::string& args :
       {"fit --data " + kTable + " --model prony --terms 2 --out " + dir + "/card.json --plot " + dir + "/fig.png",
        "eval --card " + kCard + " --frequency-hz 1,10 --out " + dir + "/eval.csv --plot " + dir + "/fig.png --data " +
            kTable,
        "plot --card " + kCard + " --data " + kTable + " --out " + dir + "/fig.png"}) {
    const CliResult r = run_with_path(empty, args, "no-gnuplot");
    EXPECT_EQ(r.exit_code, 5) << args << "\n" << r.err;
    EXPECT_NE(r.err.find("gnuplot is not on PATH"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("nothing was run or written"), std::string::npos) << r.err;
    EXPECT_EQ(files_in(dir), 0u) << args;
  }
}

TEST(Figures, GnuplotFailingAfterTheCardLeavesTheCardStandingAndExitsFive) {
  const std::string dir = temp_file("gnuplot-fails");
  fs::create_directories(dir);
  const std::string path = failing_gnuplot_dir() + ":/usr/bin:/bin";
  const std::string card = dir + "/card.json", png = dir + "/fig.png";
  const CliResult r =
      run_with_path(path, "fit --data " + kTable + " --model prony --terms 2 --out " + card + " --plot " + png, "fails");
  EXPECT_EQ(r.exit_code, 5) << r.err;
  EXPECT_NE(r.err.find("gnuplot failed (exit status 1)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the figure " + png + " was not written, the run's other outputs are"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("card written to " + card), std::string::npos) << r.out;  // the summary is printed
  EXPECT_FALSE(fs::exists(png));
  EXPECT_EQ(files_in(dir), 1u);  // the card, and no temporary PNG left behind
  const fitlib::card::Card written = fitlib::card::load_card(card);  // a whole card, usable
  EXPECT_EQ(written.values().size(), 5u);
  EXPECT_EQ(run_fitcli("eval --card " + card + " --frequency-hz 1").exit_code, 0);
  // `fitcli plot`, whose figure is its only output: exit 5 too, nothing written.
  const CliResult p = run_with_path(path, "plot --card " + kCard + " --data " + kTable + " --out " + png, "fails-plot");
  EXPECT_EQ(p.exit_code, 5) << p.err;
  EXPECT_FALSE(fs::exists(png));
  // With gnuplot found and working the same run exits 0 with both files.
  const CliResult ok = run_fitcli("fit --data " + kTable + " --model prony --terms 2 --out " + dir + "/card2.json --plot " +
                                  dir + "/fig2.png");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_EQ(slurp(dir + "/fig2.png").substr(1, 3), "PNG");
}

TEST(Inputs, OneDataFileGivenTwiceIsRefusedNamingIt) {
  const std::string dir = temp_file("twice");
  fs::create_directories(dir);
  const std::string table = dir + "/t.csv";
  fs::copy_file(kTable, table);
  fs::create_hard_link(table, dir + "/hard.csv");
  for (const std::string& again : {table, dir + "/./t.csv", dir + "/hard.csv"}) {
    const auto r = run_fitcli("fit --data " + table + " --data " + again + " --model prony --terms 2 --out " + dir +
                              "/card.json");
    EXPECT_EQ(r.exit_code, 2) << again << "\n" << r.err;
    EXPECT_NE(r.err.find("--data " + again + " is given twice (also as " + table + ")"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/card.json"));
  }
  // Two files with the same bytes are two tables (a warning says their rows count twice).
  fs::copy_file(kTable, dir + "/copy.csv");
  const auto r = run_fitcli("fit --data " + table + " --data " + dir + "/copy.csv --model prony --terms 2 --out " + dir +
                            "/card.json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("hold the same bytes"), std::string::npos) << r.err;
}

}  // namespace
