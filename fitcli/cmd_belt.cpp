// fitcli belt: run a scene's planner and write the load history and the summary.
#include <iostream>

#include "commands.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"

namespace fitcli {

void register_belt(CLI::App& app) {
  auto* cmd = app.add_subcommand("belt", "Load cycle of a drive scene: F, K, p, gamma along the path");
  auto scene_path = std::make_shared<std::string>();
  auto out_dir = std::make_shared<std::string>("belt-out");
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--scene", *scene_path, "Scene TOML (docs/formats.md §5)")->required();
  cmd->add_option("--out", *out_dir, "Output folder (load_history.csv, summary.json)");
  cmd->add_flag("--json", *json, "Print the summary as JSON on stdout");
  cmd->callback([=] {
    const auto scene = fitlib::scene::load_scene(*scene_path);
    const auto result = fitlib::scene::run_scene(scene);
    const auto files = fitlib::scene::write_outputs(scene, result, *out_dir);
    if (*json) {
      std::cout << fitlib::scene::summary_json(scene, result).dump(2) << "\n";
      return;
    }
    std::cout << "scene: " << scene.name << "\n";
    for (const auto& e : result.plan.effects)
      std::cout << "  " << (e.ran ? "ran     " : "not run ") << e.name << "  " << e.wall_s * 1e3
                << " ms  (" << e.reason << ")\n";
    if (result.cycle)
      for (const auto& p : result.cycle->pulleys)
        std::cout << "  pulley " << p.name << " (" << fitlib::belt::to_string(p.role) << "): F " << p.F_in_N
                  << " -> " << p.F_out_N << " N, sliding arc " << p.sliding_rad * 57.29577951308232
                  << " deg of " << p.wrap_rad * 57.29577951308232 << " deg (" << p.arc_method << ")\n";
    for (const auto& o : result.plan.unavailable_outputs)
      std::cerr << "fitcli: warning: output '" << o << "' is not available in this version (not run)\n";
    for (const auto& f : files) std::cout << "wrote " << f << "\n";
  });
}

}  // namespace fitcli
