// Sweep scaling (issue 9 item 4; plain main, prints its tables; docs/sweep.md "Scaling"):
// datasets/sweeps/bench-200.toml (200 beam-level life cases) and bench-4000.toml (4000) on 1 and
// 2 threads in process, and through fitcli on 1 process, 1 MPI rank and 2 MPI ranks (process
// start included); every run's
// table must equal the first byte for byte (exit 1 otherwise). Wall and CPU time per case, the
// speed-up from 1 to 2 workers, and the cost of a 10⁶-case sweep (the work cap) on N cores
// projected from the CPU time per case and the start-up of 2 ranks.
#include <sys/resource.h>
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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU seconds (user + system) of this process or of its waited-for children and their children.
double cpu_s(int who) {
  rusage u{};
  getrusage(who, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Run {
  std::string name;
  int workers = 1;
  double wall_s = 0.0, cpu_s = 0.0;  // best wall time; CPU time of that run (all processes)
  std::string table;
};

// Best of `repeats` in-process runs on `threads` threads.
Run in_process(const scene::Sweep& sweep, int threads, int repeats) {
  Run r{"in process, " + std::to_string(threads) + " thread" + (threads > 1 ? "s" : ""), threads, 1e300, 0, {}};
  for (int k = 0; k < repeats; ++k) {
    scene::ThreadExecutor ex(threads);
    scene::SweepRunOptions opt;
    opt.progress = false;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_s(RUSAGE_SELF);
    r.table = scene::run_sweep(sweep, ex, opt).table;
    if (seconds_since(t0) < r.wall_s) r.wall_s = seconds_since(t0), r.cpu_s = cpu_s(RUSAGE_SELF) - c0;
  }
  return r;
}

// Best of `repeats` runs of a fitcli command line writing `out`.
Run command(const std::string& name, int workers, const std::string& cmd, const std::string& out, int repeats) {
  Run r{name, workers, 1e300, 0, {}};
  for (int k = 0; k < repeats; ++k) {
    std::remove(out.c_str());
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpu_s(RUSAGE_CHILDREN);
    const int status = std::system((cmd + " --out " + out + " --quiet").c_str());
    const double wall = seconds_since(t0), cpu = cpu_s(RUSAGE_CHILDREN) - c0;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::printf("FAILED: %s\n", cmd.c_str());
      std::exit(1);
    }
    if (wall < r.wall_s) r.wall_s = wall, r.cpu_s = cpu;
    r.table = core::read_file(out);
  }
  return r;
}

// Best wall time of a command that does no work.
double startup_s(const std::string& cmd, int repeats) {
  double best = 1e300;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    if (std::system(cmd.c_str()) != 0) std::printf("FAILED: %s\n", cmd.c_str());
    best = std::min(best, seconds_since(t0));
  }
  return best;
}

std::string mpiexec(int ranks) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + std::string(FITLIB_MPIEXEC) +
         " --oversubscribe -n " + std::to_string(ranks) + " ";
}

std::string load_average() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? std::to_string(load[0]).substr(0, 5) : "?";
}

void print_projection(double cpu_per_case_s, const std::string& start_run, double start_s) {
  std::printf("\nProjected cost of a 10^6-case sweep (the work cap) on N otherwise idle cores: %.3g ms CPU\n"
              "per case (in process, 1 thread) plus the start-up of '%s' (%.2f s):\n\n",
              1e3 * cpu_per_case_s, start_run.c_str(), start_s);
  std::printf("| cores | wall time | core-hours |\n|---:|---:|---:|\n");
  for (int cores : {1, 2, 8, 32, 128, 512}) {
    const double wall_s = start_s + 1e6 * cpu_per_case_s / cores;
    std::printf("| %d | %.3g h | %.3g |\n", cores, wall_s / 3600, wall_s * cores / 3600);
  }
}

// Every run of one sweep file; prints its table and returns false when a table differs.
bool scaling_table(const std::string& file, int repeats, std::vector<Run>& runs, std::size_t& cases) {
  const auto sweep = scene::load_sweep(file);
  const std::string tmp = "/tmp/bench_sweep_" + std::to_string(getpid()) + ".csv";
  const std::string fitcli = std::string(FITCLI_EXE) + " sweep --sweep " + file;
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
  cases = sweep.case_count;
  std::printf("\nSweep scaling: %s, %zu cases, best of %d runs (bytes of every table compared)\n\n",
              sweep.name.c_str(), cases, repeats);
  std::printf("| run | workers | wall time | wall per case | CPU per case | speed-up vs its 1-worker run | same bytes |\n"
              "|---|---:|---:|---:|---:|---:|---|\n");
  bool same = true;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& r = runs[i];
    const Run& base = r.workers == 1 ? r : runs[i - 1];  // the 2-worker row follows its 1-worker row
    const bool equal = r.table == runs[0].table;
    same = same && equal;
    std::printf("| %s | %d | %.3f s | %.3g ms | %.3g ms | %.2f | %s |\n", r.name.c_str(), r.workers, r.wall_s,
                1e3 * r.wall_s / cases, 1e3 * r.cpu_s / cases, base.wall_s / r.wall_s, equal ? "yes" : "NO");
  }
  std::printf("\nspeed-up 1 -> 2 workers: threads %.2f", runs[0].wall_s / runs[1].wall_s);
  if (runs.size() == 5) std::printf(", MPI ranks %.2f", runs[3].wall_s / runs[4].wall_s);
  std::printf(" (load average while measured: %s)\n", load_average().c_str());
  return same;
}

}  // namespace

int main(int argc, char** argv) {
  // 200 cases (the size), then 4000 so that the MPI start-up (about 0.6 s) stops hiding
  // the scaling from 1 to 2 ranks; --quick (the ctest run) only the 200.
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  const std::string dir = std::string(FITLIB_SOURCE_DIR) + "/datasets/sweeps/";
  std::vector<Run> small, large;
  std::size_t small_cases = 0, large_cases = 0;
  bool same = scaling_table(dir + "bench-200.toml", 5, small, small_cases);
  if (quick) large = small, large_cases = small_cases;
  else same = scaling_table(dir + "bench-4000.toml", 2, large, large_cases) && same;
  // On a shared machine the wall-time speed-up measures the load as much as the code (and OpenMPI
  // spins while it waits in a collective, taking CPU from the other rank). The projection takes
  // the CPU time per case in process (1 thread: what a worker spends per case) and the start-up
  // of 2 ranks (mpiexec -n 2 fitcli --version) as a fixed cost.
  const double cpu_case = large[0].cpu_s / large_cases;
#ifdef FITLIB_MPIEXEC
  const double start_s = startup_s(mpiexec(2) + FITCLI_EXE + " --version >/dev/null", 5);
#else
  const double start_s = 0.0;
#endif
  print_projection(cpu_case, "mpiexec -n 2 fitcli --version", start_s);
  if (!same) std::printf("\nFAILED: a table differs from the first run's\n");
  return same ? 0 : 1;
}
