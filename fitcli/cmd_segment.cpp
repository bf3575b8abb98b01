// fitcli segment: a static load case of the belt segment FE (prescribed ε, K, bottom pressure).
#include <iomanip>
#include <iostream>

#include "commands.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/scene/segment_case.hpp"
#include "inputs.hpp"
#include "output.hpp"

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
    const auto r = fitlib::scene::run_segment_case(scene, *vtk);
    const auto j = fitlib::scene::segment_json(scene, r);
    if (*json) {
      std::cout << j.dump(2) << "\n";
      return;
    }
    std::cout << "segment: " << r.elements << " elements, " << r.equations << " equations, " << r.increments
              << " increments, " << r.newton_iterations << " Newton iterations, " << std::setprecision(3)
              << r.wall_s << " s\n";
    std::cout << std::setprecision(6) << "point               x_mm      y_mm   s11_radial  s22_long     s12   s_princ_max  (MPa)\n";
    for (const auto& p : r.stresses)
      std::cout << std::left << std::setw(16) << p.point.name << std::right << std::setw(8) << p.point.x_mm
                << std::setw(10) << p.point.y_mm << std::setw(12) << p.sigma11_MPa << std::setw(11) << p.sigma22_MPa
                << std::setw(12) << p.sigma12_MPa << std::setw(13) << p.principal_max_MPa << "\n";
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
