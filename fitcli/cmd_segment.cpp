// fitcli segment: a static load case of the belt segment FE (prescribed ε, K, bottom pressure).
#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/scene/output_paths.hpp"
#include "fitlib/scene/segment_case.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "path_guard.hpp"

namespace fitcli {

void register_segment(CLI::App& app) {
  auto* cmd = app.add_subcommand("segment", "Static load case of the belt segment FE ([segment] of a scene)");
  auto scene_path = std::make_shared<std::string>();
  auto vtk = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  cmd->add_option("--scene", *scene_path, "Scene file (TOML) with a [segment] table (- = stdin)")->required();
  cmd->add_option("--vtk", *vtk, "VTK file to write: the mesh with displacements and cell stresses (legacy VTK)");
  add_json_flag(cmd, *json, "the result, on stdout");
  add_verbosity_flags(cmd);
  cmd->callback([=] {
    if (*vtk == "-") throw fitlib::core::UsageError("segment --vtk needs a file (- is not supported)");
    const auto scene = load_scene_input(*scene_path);
    fitlib::scene::refuse_outputs_on_inputs(scene, {{"--vtk", *vtk}});
    const auto c = fitlib::scene::run_segment_case(scene, *vtk);
    const auto& r = c.result;
    const auto j = fitlib::scene::segment_json(scene, c);
    if (*json) {
      std::cout << j.dump(2) << "\n";
      return;
    }
    for (const auto& m : c.materials) std::cout << m.role << ": " << m.material << " (" << m.source << ")\n";
    if (c.frequency_Hz > 0.0)
      std::cout << "cards read at " << fitlib::core::format_number(c.temperature_C) << " degC, "
                << fitlib::core::format_number(c.frequency_Hz, 4) << " Hz (storage stiffness)\n";
    for (const auto& w : c.warnings) warning(w);  // stderr, as every command's
    std::cout << "segment: " << r.elements << " elements, " << r.equations << " equations, " << r.increments
              << " increments, " << r.newton_iterations << " Newton iterations, " << std::setprecision(3)
              << r.wall_s << " s\n";
    // Four significant digits and a space before every column: a value never runs into the next.
    std::size_t name_width = 5;
    for (const auto& p : r.stresses) name_width = std::max(name_width, p.point.name.size());
    char line[128];
    std::snprintf(line, sizeof line, " %8s %8s %12s %12s %12s %12s  (MPa)\n", "x_mm", "y_mm", "s11_radial", "s22_long",
                  "s12", "s_princ_max");
    std::cout << std::left << std::setw(static_cast<int>(name_width)) << "point" << line;
    for (const auto& p : r.stresses) {
      std::snprintf(line, sizeof line, " %8.4g %8.4g %12.4g %12.4g %12.4g %12.4g\n", p.point.x_mm, p.point.y_mm,
                    p.sigma11_MPa, p.sigma22_MPa, p.sigma12_MPa, p.principal_max_MPa);
      std::cout << std::setw(static_cast<int>(name_width)) << p.point.name << line;
    }
    std::cout << std::right << std::setprecision(6);
    std::cout << "cord-line reaction: Fx " << r.cord_reaction_N_mm.x() << " Fy " << r.cord_reaction_N_mm.y()
              << " N/mm, moment " << r.cord_moment_N << " N mm/mm\n";
    std::cout << "mid-length section: N " << r.mid_section.force_N_mm.x() << " N/mm, M " << r.mid_section.moment_N
              << " N mm/mm\n";
    std::cout << "section stiffness (rubber about the cord line): c " << r.c_N_per_mm << " N/mm per mm width ("
              << j["stiffness"]["c_N"].get<double>() << " N), EI " << r.EI_Nmm2_per_mm << " N mm2 per mm width ("
              << j["stiffness"]["EI_Nmm2"].get<double>() << " N mm2)\n";
    if (!vtk->empty()) std::cout << "wrote " << *vtk << "\n";
  });
}

}  // namespace fitcli
