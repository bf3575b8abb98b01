// fitcli belt: run a scene's planner and write the load history and the summary.
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "path_guard.hpp"
#include "plot.hpp"

namespace fitcli {

void register_belt(CLI::App& app) {
  auto* cmd = app.add_subcommand("belt", "Load cycle of a drive scene: F, K, p, gamma along the path");
  auto scene_path = std::make_shared<std::string>();
  auto out_dir = std::make_shared<std::string>("belt-out");
  auto json = std::make_shared<bool>(false);
  auto record_timing = std::make_shared<bool>(false);
  auto plot = std::make_shared<std::string>();
  cmd->add_option("--scene", *scene_path, "Scene file (TOML, docs/formats.md §5; - = stdin)")->required();
  cmd->add_option("--out-dir", *out_dir, "Output folder (load_history.csv, summary.json)")->capture_default_str();
  // Deprecated spelling (one release): --out names a file in every other subcommand.
  cmd->add_option("--out", *out_dir)->group("");
  add_json_flag(cmd, *json, "the summary, on stdout");
  add_verbosity_flags(cmd);
  cmd->add_flag("--record-timing", *record_timing, "Store wall times in summary.json (breaks byte-identity)");
  cmd->add_option("--plot", *plot,
                  "Also write the figure (PNG): belt force and curvature, side pressure and friction used, sliding "
                  "angle and speed over the load cycle, the pulleys' contact shaded");
  cmd->callback([=] {
    if (cmd->count("--out") > 0 && cmd->count("--out-dir") > 0)
      throw fitlib::core::UsageError("belt: give --out-dir only (--out DIR is its deprecated spelling)");
    // --out names a file in every other subcommand: a name with an extension (lh.csv) was meant as
    // one, and would become a folder of that name.
    if (cmd->count("--out") > 0 && std::filesystem::path(*out_dir).has_extension())
      throw fitlib::core::UsageError("belt writes a folder (load_history.csv, summary.json, …), not the file '" +
                                     *out_dir + "': use --out-dir DIR (docs/cli.md)");
    if (cmd->count("--out") > 0) note("belt --out DIR is deprecated: use --out-dir DIR (docs/cli.md)");
    const auto scene = load_scene_input(*scene_path);
    refuse_out_dir_collisions(scene, *out_dir, {{"--plot", *plot}});
    if (!plot->empty()) claim_png("--plot", *plot, *out_dir);
    fitlib::core::prepare_output_dir(*out_dir);
    const auto result = fitlib::scene::run_scene(scene);
    auto files = fitlib::scene::write_outputs(scene, result, *out_dir, *record_timing);
    if (!plot->empty() && result.cycle && draw_figure(*plot, [&] {
          write_png(*plot, [&](const std::string& tmp) { return belt_plot_script(scene, *result.cycle, tmp); });
        }))
      files.push_back(*plot);
    if (*json) {
      std::cout << fitlib::scene::summary_json(scene, result, *record_timing).dump(2) << "\n";
      return;
    }
    std::cout << "scene: " << scene.name << "\n";
    std::cout << fitlib::scene::effects_table(result.plan);
    if (result.cycle)
      for (const auto& p : result.cycle->pulleys)
        std::cout << "  pulley " << p.name << " (" << fitlib::belt::to_string(p.role) << "): F " << p.F_in_N
                  << " -> " << p.F_out_N << " N, sliding arc " << p.sliding_rad * 57.29577951308232
                  << " deg of " << p.wrap_rad * 57.29577951308232 << " deg (" << p.arc_method << ")\n";
    for (const auto& o : result.plan.unavailable_outputs)
      warning("output '" + o + "' is not available in this version (not run)");
    for (const auto& w : result.warnings) warning(w);
    for (const auto& f : files) std::cout << "wrote " << f << "\n";
  });
}

}  // namespace fitcli
