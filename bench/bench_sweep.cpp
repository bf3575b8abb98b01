// Sweep scaling (issue 9 item 4; plain main, prints its table; docs/sweep.md "Scaling"):
// datasets/sweeps/bench-200.toml (200 beam-level life cases) on 1 and 2 threads in process, and
// through fitcli on 1 process, 1 MPI rank and 2 MPI ranks (process start included); every run's
// table must equal the first byte for byte (exit 1 otherwise). From the best per-case time on one
// worker and the measured 2-worker efficiency it projects the wall time of a 10⁶-case sweep
// (the work cap) on N cores.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fitlib/core/io.hpp"
#include "fitlib/scene/sweep_run.hpp"

using namespace fitlib;

namespace {

const std::string kSweep = std::string(FITLIB_SOURCE_DIR) + "/datasets/sweeps/bench-200.toml";

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Run {
  std::string name;
  int workers = 1;
  double wall_s = 0.0;
  std::string table;
};

// Best of `repeats` in-process runs on `threads` threads.
Run in_process(const scene::Sweep& sweep, int threads, int repeats) {
  Run r{"in process, " + std::to_string(threads) + " thread" + (threads > 1 ? "s" : ""), threads, 1e300, {}};
  for (int k = 0; k < repeats; ++k) {
    scene::ThreadExecutor ex(threads);
    scene::SweepRunOptions opt;
    opt.progress = false;
    const auto t0 = std::chrono::steady_clock::now();
    r.table = scene::run_sweep(sweep, ex, opt).table;
    r.wall_s = std::min(r.wall_s, seconds_since(t0));
  }
  return r;
}

// Best of `repeats` runs of a fitcli command line writing `out`.
Run command(const std::string& name, int workers, const std::string& cmd, const std::string& out, int repeats) {
  Run r{name, workers, 1e300, {}};
  for (int k = 0; k < repeats; ++k) {
    std::remove(out.c_str());
    const auto t0 = std::chrono::steady_clock::now();
    const int status = std::system((cmd + " --out " + out + " --quiet").c_str());
    const double wall = seconds_since(t0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::printf("FAILED: %s\n", cmd.c_str());
      std::exit(1);
    }
    r.wall_s = std::min(r.wall_s, wall);
    r.table = core::read_file(out);
  }
  return r;
}

std::string mpiexec(int ranks) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + std::string(FITLIB_MPIEXEC) +
         " --oversubscribe -n " + std::to_string(ranks) + " ";
}

void print_projection(double per_case_s, double efficiency) {
  std::printf("\nProjected wall time of a 10^6-case sweep (the work cap) from %.3g ms per case on one worker\n"
              "and %.0f %% parallel efficiency at 2 workers (assumed to hold on N cores):\n\n",
              1e3 * per_case_s, 100 * efficiency);
  std::printf("| cores | wall time | core-hours |\n|---:|---:|---:|\n");
  for (int cores : {1, 2, 8, 32, 128, 512}) {
    const double eff = cores == 1 ? 1.0 : efficiency;
    const double wall_s = 1e6 * per_case_s / (cores * eff);
    std::printf("| %d | %.3g h | %.3g |\n", cores, wall_s / 3600, wall_s * cores / 3600);
  }
}

}  // namespace

int main() {
  const auto sweep = scene::load_sweep(kSweep);
  const std::string tmp = "/tmp/bench_sweep_" + std::to_string(getpid()) + ".csv";
  const std::string fitcli = std::string(FITCLI_EXE) + " sweep --sweep " + kSweep;
  const int repeats = 3;
  std::vector<Run> runs;
  runs.push_back(in_process(sweep, 1, repeats));
  runs.push_back(in_process(sweep, 2, repeats));
  runs.push_back(command("fitcli, 1 process, 1 thread", 1, fitcli + " --threads 1", tmp, repeats));
#ifdef FITLIB_MPIEXEC
  runs.push_back(command("mpiexec -n 1 fitcli", 1, mpiexec(1) + fitcli, tmp, repeats));
  runs.push_back(command("mpiexec -n 2 fitcli", 2, mpiexec(2) + fitcli, tmp, repeats));
#else
  std::printf("(built without MPI: no rank rows)\n");
#endif
  std::remove(tmp.c_str());
  std::printf("Sweep scaling: %s, %zu cases, best of %d runs (bytes of every table compared)\n\n",
              sweep.name.c_str(), sweep.case_count, repeats);
  std::printf("| run | workers | wall time | per case | speed-up vs its 1-worker run | same bytes |\n"
              "|---|---:|---:|---:|---:|---|\n");
  bool same = true;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& r = runs[i];
    const Run& base = r.workers == 1 ? r : runs[i - 1];  // the 2-worker row follows its 1-worker row
    const bool equal = r.table == runs[0].table;
    same = same && equal;
    std::printf("| %s | %d | %.3f s | %.3g ms | %.2f | %s |\n", r.name.c_str(), r.workers, r.wall_s,
                1e3 * r.wall_s / sweep.case_count, base.wall_s / r.wall_s, equal ? "yes" : "NO");
  }
  // Efficiency at 2 workers: threads in process, and MPI ranks with process start; the lower one
  // (the conservative one) projects.
  const double per_case = runs[0].wall_s / sweep.case_count;
  double efficiency = runs[0].wall_s / runs[1].wall_s / 2.0;
  std::printf("\n2-worker efficiency: threads %.0f %%", 100 * efficiency);
  if (runs.size() == 5) {
    const double mpi = runs[3].wall_s / runs[4].wall_s / 2.0;
    std::printf(", MPI ranks %.0f %%", 100 * mpi);
    efficiency = std::min(efficiency, mpi);
  }
  std::printf("\n");
  print_projection(per_case, efficiency);
  if (!same) std::printf("\nFAILED: a table differs from the first run's\n");
  return same ? 0 : 1;
}
