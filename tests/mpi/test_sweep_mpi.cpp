// fitcli sweep under mpiexec with 2 ranks on this machine: the same bytes as the threaded run
// (docs/sweep.md "MPI"). Built when CMake finds MPI (FITLIB_MPI) as test_sweep_mpi; fails, never skips, when
// mpiexec is missing (scripts/install-deps.sh installs openmpi-bin).
#ifdef FITLIB_MPIEXEC
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "fitlib/card/card.hpp"
#include "fitlib/fatigue/card.hpp"
#include "integration/cli_runner.hpp"

namespace {

// OpenMPI as root in a container on 2 cores: allow root, more ranks than cores, shared-memory
// transport without the single-copy mechanism (docs/sweep.md "MPI").
std::string mpiexec(int ranks, const std::string& fitcli_args) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none " +
         std::string(FITLIB_MPIEXEC) + " --oversubscribe -n " + std::to_string(ranks) + " " + FITCLI_EXE + " " +
         fitcli_args;
}

int run(const std::string& cmd, const std::string& log) {
  const int status = std::system((cmd + " >" + log + " 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(SweepMpi, TwoRanksWriteTheThreadedBytes) {
  ASSERT_TRUE(std::filesystem::exists(FITLIB_MPIEXEC)) << FITLIB_MPIEXEC << " missing: install openmpi-bin";
  const std::string sweep = source_path("tests/data/sweep/small.toml");
  const std::string tag = std::to_string(getpid());
  const std::string threaded = temp_file("threaded-" + tag + ".csv"), mpi = temp_file("mpi-" + tag + ".csv");
  const auto r = run_fitcli("sweep --sweep " + sweep + " --out " + threaded + " --threads 2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string log = temp_file("mpi-" + tag + ".log");
  ASSERT_EQ(run(mpiexec(2, "sweep --sweep " + sweep + " --out " + mpi + " --verbose"), log), 0) << slurp(log);
  EXPECT_NE(slurp(log).find("24 cases, 2 workers"), std::string::npos) << slurp(log);
  EXPECT_EQ(slurp(mpi), slurp(threaded));
}

TEST(SweepMpi, TwoRanksResumeAThreadedPartialFile) {
  const std::string sweep = source_path("tests/data/sweep/small.toml");
  const std::string tag = std::to_string(getpid());
  const std::string whole = temp_file("whole-" + tag + ".csv"), out = temp_file("resume-" + tag + ".csv");
  ASSERT_EQ(run_fitcli("sweep --sweep " + sweep + " --out " + whole + " --quiet").exit_code, 0);
  ASSERT_EQ(run_fitcli("sweep --sweep " + sweep + " --out " + out + " --threads 1 --quiet --stop-after 5").exit_code, 0);
  const std::string log = temp_file("resume-" + tag + ".log");
  ASSERT_EQ(run(mpiexec(2, "sweep --sweep " + sweep + " --out " + out), log), 0) << slurp(log);
  EXPECT_NE(slurp(log).find("5 read back"), std::string::npos) << slurp(log);
  EXPECT_EQ(slurp(out), slurp(whole));
}
namespace {

// The medium drive at the beam level with draws of the cards: the bottom card is the thesis card
// with a covariance of its mean moduli (ln, variance 4e-3, correlation 0.5), the fatigue card
// Report I's constants with a scatter and a covariance; `extra` is appended to the scene.
std::string draws_scene(const std::string& name, int samples, const std::string& extra) {
  const std::string tag = name + "-" + std::to_string(getpid());
  fitlib::card::Card bottom = fitlib::card::load_card(source_path("datasets/cards/material-1-true.json"));
  const double v = 4e-3, r = 0.5 * v;
  bottom.fit["covariance"] = {{"parameters", {"G_Im", "C33_Am", "C44_Am"}},
                              {"coordinates", {"ln", "ln", "ln"}},
                              {"matrix", {{v, r, r}, {r, v, r}, {r, r, v}}}};
  const std::string bottom_path = temp_file("draws-bottom-" + tag + ".json");
  fitlib::card::save_card(bottom_path, bottom);
  fitlib::fatigue::FatigueCard law = fitlib::fatigue::default_card();
  law.radial_crack.scatter = fitlib::fatigue::LifeScatter{"lognormal", 0.3, 12};
  law.separation.scatter = fitlib::fatigue::LifeScatter{"lognormal", 0.25, 10};
  law.separation.covariance = fitlib::fatigue::LawCovariance{{{1e-3, 0.0, 0.0}, {0.0, 0.04, 0.0}, {0.0, 0.0, 1e-5}}};
  const std::string law_path = temp_file("draws-law-" + tag + ".json");
  fitlib::fatigue::save_card(law_path, law);
  const std::string scene = temp_file("draws-" + tag + ".toml");
  std::ofstream(scene) << slurp(source_path("datasets/drives/ref-0500-medium.toml")) << "\n[belt.materials]\nbottom = \""
                       << bottom_path << "\"\n\n[life]\nfidelity = \"beam\"\ncard = \"" << law_path
                       << "\"\nuncertainty = \"constants+cards\"\nsamples = " << samples << "\nseed = 5\n" << extra;
  return scene;
}

}  // namespace

// [life] uncertainty = "constants+cards" (docs/thermal.md §7) under mpiexec: the card draws run
// across 2 ranks (draw k on rank k mod 2), rank 0 alone runs the deterministic life and writes
// life.json and summary.json, the same bytes as the threaded run of the same seed: 30 draws at the
// beam level.
TEST(SweepMpi, LifeCardDrawsOnTwoRanksWriteTheThreadedBytes) {
  ASSERT_TRUE(std::filesystem::exists(FITLIB_MPIEXEC)) << FITLIB_MPIEXEC << " missing: install openmpi-bin";
  const std::string tag = std::to_string(getpid()), scene = draws_scene("bytes", 30, "");
  const std::string threaded = temp_file("draws-threaded-" + tag), mpi = temp_file("draws-mpi-" + tag);
  const auto t = run_fitcli("life --scene " + scene + " --out-dir " + threaded + " --quiet");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const std::string log = temp_file("draws-mpi-" + tag + ".log");
  ASSERT_EQ(run(mpiexec(2, "life --scene " + scene + " --out-dir " + mpi + " --verbose"), log), 0) << slurp(log);
  EXPECT_NE(slurp(log).find("life: 2 MPI ranks"), std::string::npos) << slurp(log);
  const std::string json = slurp(threaded + "/life.json");
  EXPECT_NE(json.find("ci90_combined_h"), std::string::npos) << json;
  EXPECT_NE(json.find("\"draws\": 30"), std::string::npos) << json;
  EXPECT_EQ(slurp(mpi + "/life.json"), json);
  EXPECT_EQ(slurp(mpi + "/summary.json"), slurp(threaded + "/summary.json"));
  EXPECT_NE(slurp(log).find("combined ["), std::string::npos) << slurp(log);  // rank 0 printed the table
}

// With heat build-up the writer's draws start from the scene at its belt temperature and rank 1's
// from the scene as written (it runs no deterministic life): the heat's fixed point starts from the
// ambient either way, so the bytes are the threaded run's. And a writer whose deterministic life
// stops (a thermal runaway at its first iterate) still joins the draws' gather: mpiexec ends with
// its exit 4 and its message instead of rank 1 waiting for it forever.
TEST(SweepMpi, LifeCardDrawsWithHeatBuildupAndAWriterThatStops) {
  ASSERT_TRUE(std::filesystem::exists(FITLIB_MPIEXEC)) << FITLIB_MPIEXEC << " missing: install openmpi-bin";
  const std::string tag = std::to_string(getpid());
  std::string text = slurp(draws_scene("heat", 6, ""));
  text.replace(text.find("[conditions]\n"), 13, "[conditions]\nambient_C = 25\n");
  text.replace(text.find("[effects]\n"), 10, "[effects]\nheat_buildup = true\n");
  const std::string scene = temp_file("draws-heat-" + tag + ".toml");
  std::ofstream(scene) << text;
  const std::string threaded = temp_file("draws-heat-threaded-" + tag), mpi = temp_file("draws-heat-mpi-" + tag);
  const auto t = run_fitcli("life --scene " + scene + " --out-dir " + threaded + " --quiet");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(slurp(threaded + "/life.json").find("\"heat_buildup\""), std::string::npos);
  const std::string log = temp_file("draws-heat-mpi-" + tag + ".log");
  ASSERT_EQ(run(mpiexec(2, "life --scene " + scene + " --out-dir " + mpi + " --quiet"), log), 0) << slurp(log);
  EXPECT_EQ(slurp(mpi + "/life.json"), slurp(threaded + "/life.json"));
  const std::string runaway = temp_file("draws-runaway-" + tag + ".toml");
  std::ofstream(runaway) << text << "\n[thermal]\nmax_temperature_C = 26\n";
  const std::string stop_log = temp_file("draws-runaway-" + tag + ".log");
  EXPECT_EQ(run("timeout 120 env " + mpiexec(2, "life --scene " + runaway + " --out-dir " + mpi + "-stop --quiet"), stop_log), 4)
      << slurp(stop_log);
  EXPECT_NE(slurp(stop_log).find("thermal runaway"), std::string::npos) << slurp(stop_log);
}
#endif  // FITLIB_MPIEXEC
