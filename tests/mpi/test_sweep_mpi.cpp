// fitcli sweep under mpiexec with 2 ranks on this machine: the same bytes as the threaded run
// (docs/sweep.md "MPI"). Built when CMake finds MPI (FITLIB_MPI) as test_sweep_mpi; fails, never skips, when
// mpiexec is missing (scripts/install-deps.sh installs openmpi-bin).
#ifdef FITLIB_MPIEXEC
#include <unistd.h>

#include <filesystem>

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
#endif  // FITLIB_MPIEXEC
