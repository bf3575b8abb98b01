// fitcli life: a scene's fatigue life — life per mode in cycles and hours, governing mode,
// design points, the effects that ran and the cost of each (the table always shows wall times;
// life.json and summary.json in DIR only with --record-timing, so that files stay byte-identical).
// Under mpirun the [life] uncertainty = "cards" draws run across the ranks (docs/sweep.md "MPI"):
// rank 0 alone runs the deterministic life and writes, the others only their share of the draws.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "mpi_program.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "path_guard.hpp"
#include "plot.hpp"
#ifdef FITLIB_HAVE_MPI
#include "fitlib/mpi/sweep_mpi.hpp"
#endif

namespace fitcli {
namespace {

// The segment run writes the fields into DIR, so it must exist before the run; a folder made here
// is removed again when the run fails (e.g. a --field-at position beyond the load cycle). A process
// that does not write (an MPI rank but 0) runs only its share of the card draws: nullopt.
std::optional<fitlib::scene::SceneResult> run_with_field_folder(const fitlib::scene::Scene& scene, bool writer,
                                                                const std::string& out_dir) {
  if (scene.life_field_at.empty()) return fitlib::scene::run_life_sharing_draws(scene, writer);
  const bool existed = std::filesystem::exists(out_dir);
  fitlib::core::prepare_output_dir(out_dir);
  try {
    return fitlib::scene::run_life_sharing_draws(scene, writer);
  } catch (...) {
    std::error_code ec;
    if (!existed) std::filesystem::remove_all(out_dir, ec);
    throw;
  }
}

}  // namespace

void register_life(CLI::App& app) {
  auto* cmd = app.add_subcommand("life", "Fatigue life of a drive scene: life per mode, governing mode, hours");
  auto scene_path = std::make_shared<std::string>();
  auto out_dir = std::make_shared<std::string>("life-out");
  auto json = std::make_shared<bool>(false);
  auto record_timing = std::make_shared<bool>(false);
  auto field_at = std::make_shared<std::vector<std::string>>();
  auto plot = std::make_shared<std::string>();
  cmd->add_option("--scene", *scene_path, "Scene file (TOML, docs/formats.md §5; [life] optional; - = stdin)")
      ->required();
  cmd->add_option("--out-dir", *out_dir, "Output folder (life.json, summary.json)")->capture_default_str();
  auto misspelt_out = std::make_shared<std::string>();  // --out is a file everywhere (docs/cli.md)
  cmd->add_option("--out", *misspelt_out)->group("");
  add_json_flag(cmd, *json, "life.json, on stdout");
  add_verbosity_flags(cmd);
  cmd->add_option("--field-at", *field_at,
                  "Write the segment's full-field stress (VTK, DIR/field-<k>.vtk) when its middle reaches this path "
                  "position of the last cycle: 'entrance' (the first pulley's) or mm; repeatable; segment levels only");
  cmd->add_option("--plot", *plot,
                  "Also write the figure (PNG): the load cycle and each mode's effective stress at its design point "
                  "with the peaks of its sum");
  cmd->add_flag("--record-timing", *record_timing,
                "Store each effect's wall time in life.json and summary.json (breaks byte-identity)");
  cmd->callback([=] {
    become_mpi_program_under_mpirun("life");  // [life] uncertainty's draws across the ranks
    if (cmd->count("--out") > 0)
      throw fitlib::core::UsageError("life writes a folder: use --out-dir " + *misspelt_out +
                                     " (--out names a file in every subcommand, docs/cli.md)");
#ifdef FITLIB_HAVE_MPI
    const bool under_mpi = fitlib::mpi::launched_by_mpirun();
    if (under_mpi && *scene_path == "-")  // mpirun gives stdin to rank 0 alone
      throw fitlib::core::UsageError("--scene - under mpirun: give the scene as a file (every rank reads it)");
#endif
    auto scene = load_scene_input(*scene_path);
    scene.segment_progress = !quiet();  // shown only when stderr is a terminal
    bool writer = true;  // the one process that writes (rank 0 under mpirun)
#ifdef FITLIB_HAVE_MPI
    std::optional<fitlib::mpi::Session> session;  // joins after the scene is read: a bad scene fails on every rank alike
    if (under_mpi) {
      session.emplace();  // one thread per rank, as in the sweep: mpirun places the ranks on cores
      scene.draw_executor = std::make_shared<fitlib::mpi::MpiIndexedExecutor>(*session, 1);
      scene.segment_thread_cap = 1;
      writer = session->rank() == 0;
      if (!writer) scene.segment_progress = false, field_at->clear();
      if (writer && verbose())
        std::cerr << "life: " << session->size() << " MPI ranks ([life] uncertainty's card draws run across them)\n";
    }
#endif
    if (!field_at->empty()) {
      scene.life_field_at = *field_at;
      scene.life_field_prefix = (std::filesystem::path(*out_dir) / "field").string();
      fitlib::scene::check_life_fields(scene);  // exit 2 before any folder is made
    }
    refuse_out_dir_collisions(scene, *out_dir, {{"--plot", *plot}});  // the field files too
    if (!plot->empty()) claim_png("--plot", *plot, *out_dir);  // e.g. --plot DIR/life.png
    const auto run = run_with_field_folder(scene, writer, *out_dir);
    if (!writer) return;
    const fitlib::scene::SceneResult& result = *run;
    const auto files = fitlib::scene::write_outputs(scene, result, *out_dir, *record_timing);
    if (!plot->empty() && result.cycle)
      draw_figure(*plot, [&] {
        write_png(*plot, [&](const std::string& tmp) { return life_plot_script(scene, result, tmp); });
      });
    if (*json) {
      std::cout << fitlib::scene::life_json(scene, result, *record_timing).dump(2) << "\n";
      return;
    }
    std::cout << without_warnings(fitlib::scene::life_text(scene, result)) << "effects:\n"
              << fitlib::scene::effects_table(result.plan);
    for (const auto& f : files) std::cout << "wrote " << f << "\n";
  });
}

}  // namespace fitcli
