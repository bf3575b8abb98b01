// fitcli sweep: a grid of scene runs from a sweep file (docs/sweep.md) as one CSV table (or JSON
// with --json), on threads, or across MPI ranks under mpirun; resumable through --out FILE.
#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "commands.hpp"
#include "fitlib/core/error.hpp"
#include "output.hpp"
#include "fitlib/scene/sweep_run.hpp"
#ifdef FITLIB_HAVE_MPI
#include "fitlib/mpi/sweep_mpi.hpp"
#endif
#include "mpi_program.hpp"

namespace fitcli {
namespace {

struct SweepArgs {
  std::string sweep, out = "-";
  bool json = false;
  int threads = 0;
  std::size_t stop_after = 0;
};

void run(const SweepArgs& a) {
  become_mpi_program_under_mpirun("sweep");
  const bool to_file = a.out != "-";
  fitlib::scene::SweepRunOptions options;
  options.out_path = to_file ? a.out : "";
  options.progress = !quiet();
  options.stop_after = a.stop_after;
  const auto sweep = fitlib::scene::load_sweep(a.sweep);
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::unique_ptr<fitlib::scene::SweepExecutor> executor;
#ifdef FITLIB_HAVE_MPI
  std::optional<fitlib::mpi::Session> session;
  if (fitlib::mpi::launched_by_mpirun()) {
    session.emplace();  // one thread per rank unless --threads: mpirun places the ranks on cores
    executor = std::make_unique<fitlib::mpi::MpiExecutor>(*session, a.threads > 0 ? a.threads : 1);
  }
#endif
  if (!executor) executor = std::make_unique<fitlib::scene::ThreadExecutor>(a.threads > 0 ? a.threads : hardware);
  if (verbose() && executor->writes())
    std::cerr << "sweep: " << sweep.case_count << " cases, " << executor->workers() << " workers, sha256 "
              << sweep.sha256 << "\n";
  const auto result = fitlib::scene::run_sweep(sweep, *executor, options);
  if (!executor->writes()) return;
  if (!result.complete) {
    std::cerr << "sweep: stopped after " << a.stop_after << " cases (--stop-after); run again to resume\n";
    return;
  }
  if (a.json) emit("-", fitlib::scene::sweep_json(sweep, result.table).dump(2) + "\n");
  else if (!to_file) emit("-", result.table);
  if (to_file && !quiet())
    std::cerr << "wrote " << a.out << " (" << sweep.case_count << " cases, " << result.resumed << " read back)\n";
}

}  // namespace

void register_sweep(CLI::App& app) {
  auto* cmd = app.add_subcommand("sweep", "Grid of scene runs (scenes x cards x temperatures x loads) as one table");
  auto a = std::make_shared<SweepArgs>();
  cmd->add_option("--sweep", a->sweep, "Sweep file (TOML, docs/sweep.md)")->required();
  cmd->add_option("--out", a->out, "Result CSV file, resumable (- = stdout, the default; no resume)");
  add_json_flag(cmd, a->json, "the table, on stdout");
  cmd->add_option("--threads", a->threads, "Threads per process (default: all cores; 1 per rank under mpirun)")
      ->check(CLI::Range(1, 1024));
  add_verbosity_flags(cmd);  // --quiet: no progress; --verbose: grid size, workers and sweep hash
  cmd->add_option("--stop-after", a->stop_after, "Tests: stop once N cases are done, as if killed")->group("");
  cmd->callback([a, cmd] {
    if (a->json && cmd->count("--out") > 0 && a->out == "-")  // the CSV was dropped for the JSON
      throw fitlib::core::UsageError("--out - and --json both write stdout: give --out a file");
    run(*a);
  });
}

}  // namespace fitcli
