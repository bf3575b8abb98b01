// fitcli sweep end to end (docs/sweep.md): the same bytes for 1, 2 and 4 threads, a stopped
// sweep resumed to the bytes of an uninterrupted one, JSON equal to the CSV, progress on stderr.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace {

const std::string kSweep = source_path("tests/data/sweep/small.toml");

std::string out_file(const std::string& name) { return temp_file(name + "-" + std::to_string(getpid()) + ".csv"); }

std::string run_to_file(const std::string& name, const std::string& extra) {
  const std::string out = out_file(name);
  const auto r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --quiet " + extra);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  return slurp(out);
}

}  // namespace

TEST(SweepCli, SameBytesForOneTwoAndFourThreads) {
  const std::string one = run_to_file("t1", "--threads 1");
  EXPECT_EQ(run_to_file("t2", "--threads 2"), one);
  EXPECT_EQ(run_to_file("t4", "--threads 4"), one);
  // Comment line with the hash, header, 24 rows in case order.
  std::istringstream in(one);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("# fitlib sweep sha256=", 0), 0u) << line;
  std::getline(in, line);
  EXPECT_EQ(line, "case,scene,belt.materials.bottom,conditions.temperature_C,drive.torque_Nm,max_tension_N,"
                  "max_sliding_arc_deg,governing_mode,life_h,radial_crack_life_cycles,separation_life_h,"
                  "cord_break_life_h,status,message");
  int rows = 0, ok = 0, bad = 0;
  while (std::getline(in, line)) {
    EXPECT_EQ(line.rfind(std::to_string(rows) + ",", 0), 0u) << line;
    ok += line.find(",ok,") != std::string::npos;
    bad += line.find(",input_error,") != std::string::npos;
    EXPECT_EQ(line.find("nan"), std::string::npos);
    EXPECT_EQ(line.find("inf"), std::string::npos);
    ++rows;
  }
  EXPECT_EQ(rows, 24);
  EXPECT_EQ(ok, 16);  // 400 N·m slips in every scene, card and temperature
  EXPECT_EQ(bad, 8);
}

TEST(SweepCli, StoppedSweepResumesToTheSameBytes) {
  const std::string whole = run_to_file("whole", "--threads 2");
  const std::string out = out_file("resumed");
  auto r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 1 --quiet --stop-after 9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out));  // only the unfinished FILE.partial
  // FILE.partial: the table's lines with one more field each, the row's row_sha256 (docs/sweep.md)
  const std::string partial = slurp(out + ".partial");
  std::string rows;
  std::istringstream lines(partial);
  for (std::string line; std::getline(lines, line);) rows += line.substr(0, line.rfind(',')) + "\n";
  ASSERT_LT(rows.size(), whole.size());
  EXPECT_EQ(whole.compare(0, rows.size(), rows), 0);
  EXPECT_NE(partial.find(",row_sha256\n"), std::string::npos);
  // A kill in the middle of a row: the cut line is dropped and recomputed.
  std::ofstream(out + ".partial", std::ios::app) << whole.substr(rows.size(), 17);
  r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("(24 cases, 9 read back)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sweep: 24/24 cases"), std::string::npos) << r.err;  // progress
  EXPECT_EQ(slurp(out), whole);
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));
}

std::size_t line_count(const std::string& path) {
  const std::string text = slurp(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

// A real kill: SIGTERM once some rows are flushed. Should the sweep finish first (a fast machine),
// the restart redoes it; either way the final bytes must equal an uninterrupted run's.
TEST(SweepCli, KilledSweepResumesToTheSameBytes) {
  const std::string sweep = source_path("tests/data/sweep/long.toml");
  const std::string whole = out_file("long_whole"), out = out_file("long_killed");
  ASSERT_EQ(run_fitcli("sweep --sweep " + sweep + " --out " + whole + " --threads 2 --quiet").exit_code, 0);
  const pid_t pid = fork();
  if (pid == 0) {
    execl(FITCLI_EXE, FITCLI_EXE, "sweep", "--sweep", sweep.c_str(), "--out", out.c_str(), "--threads", "1",
          "--quiet", static_cast<char*>(nullptr));
    _exit(127);
  }
  for (int i = 0; i < 4000 && line_count(out + ".partial") < 6; ++i) usleep(2000);
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) {
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_LT(line_count(out + ".partial"), 1002u);
  }
  const auto r = run_fitcli("sweep --sweep " + sweep + " --out " + out + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(out), slurp(whole));
  std::printf("[ killed   ] %s; restart: %s", WIFSIGNALED(status) ? "by SIGTERM" : "finished first",
              r.err.substr(r.err.rfind("wrote")).c_str());
}

TEST(SweepCli, PartialFileOfAnotherSweepIsRefused) {
  const std::string out = out_file("other");
  std::ofstream(out + ".partial") << "# fitlib sweep sha256=0000 cases=3\ncase,scene\n";
  const auto r = run_fitcli("sweep --sweep " + kSweep + " --out " + out + " --quiet");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find(out + ".partial:1:1"), std::string::npos) << r.err;
}

TEST(SweepCli, JsonHoldsTheTableRows) {
  const std::string csv = run_to_file("json_csv", "--threads 2");
  const auto r = run_fitcli("sweep --sweep " + kSweep + " --json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["cases"], 24);
  ASSERT_EQ(j["rows"].size(), 24u);
  EXPECT_NE(csv.find(j["sha256"].get<std::string>()), std::string::npos);
  const auto& first = j["rows"][0];
  EXPECT_EQ(first["case"], 0);
  EXPECT_EQ(first["drive.torque_Nm"], 12);
  EXPECT_EQ(first["conditions.temperature_C"], 40);
  EXPECT_EQ(first["status"], "ok");
  EXPECT_TRUE(first["life_h"].is_number());
  EXPECT_TRUE(j["rows"][2]["max_tension_N"].is_null());  // 400 N·m: input_error
  EXPECT_EQ(j["rows"][2]["status"], "input_error");
  // Numbers read back from the CSV text exactly.
  std::istringstream in(csv);
  std::string line;
  for (int i = 0; i < 3; ++i) std::getline(in, line);
  std::vector<std::string> fields;
  for (std::size_t a = 0, b; a <= line.size(); a = b + 1) {
    b = std::min(line.find(',', a), line.size());
    fields.push_back(line.substr(a, b - a));
  }
  ASSERT_GT(fields.size(), 5u);
  EXPECT_EQ(std::strtod(fields[5].c_str(), nullptr), first["max_tension_N"].get<double>()) << line;
}

TEST(SweepCli, CsvOnStdoutWithoutOut) {
  const std::string file = run_to_file("stdout_ref", "--threads 2");
  const auto r = run_fitcli("sweep --sweep " + kSweep + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, file);
  EXPECT_NE(r.err.find("sweep: 24/24 cases"), std::string::npos) << r.err;
}
