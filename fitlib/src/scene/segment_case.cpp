#include "fitlib/scene/segment_case.hpp"

#include "fitlib/core/error.hpp"
#include "fitlib/core/finite_output.hpp"

namespace fitlib::scene {

segment::StaticResult run_segment_case(const Scene& scene, const std::string& vtk_path) {
  if (!scene.segment) throw core::InputError("the scene has no [segment] table", scene.path, 0, 0, "segment");
  segment::StaticSolution solution;
  segment::Mesh mesh;
  const auto result = segment::run_static_case(scene.segment->setup, scene.segment->load, &solution, &mesh);
  if (!vtk_path.empty()) {
    segment::VtkFields f;
    f.displacement_mm = solution.u_mm;
    for (const auto& el : solution.points) {
      std::array<double, 4> mean{};
      for (const auto& g : el) {
        mean[0] += g.cauchy_MPa(0, 0) / el.size(), mean[1] += g.cauchy_MPa(1, 1) / el.size();
        mean[2] += g.cauchy_MPa(0, 1) / el.size(), mean[3] += g.sigma33_MPa / el.size();
      }
      f.cell_stress_MPa.push_back(mean);
    }
    segment::write_vtk(mesh, vtk_path, f);
  }
  return result;
}

nlohmann::json segment_json(const Scene& scene, const segment::StaticResult& r) {
  const auto& load = scene.segment->load;
  nlohmann::json j;
  j["scene"] = scene.name;
  j["load"] = {{"strain", load.strain}, {"curvature_1_mm", load.curvature_1_mm}, {"pressure_MPa", load.pressure_MPa}};
  j["mesh"] = {{"elements", r.elements}, {"nodes", r.nodes}, {"equations", r.equations}};
  j["solver"] = {{"increments", r.increments}, {"newton_iterations", r.newton_iterations}};
  for (const auto& p : r.stresses)
    j["points"].push_back({{"name", p.point.name}, {"x_mm", p.point.x_mm}, {"y_mm", p.point.y_mm},
                           {"sigma11_radial_MPa", p.sigma11_MPa}, {"sigma22_longitudinal_MPa", p.sigma22_MPa},
                           {"sigma12_MPa", p.sigma12_MPa}, {"sigma33_MPa", p.sigma33_MPa},
                           {"principal_max_MPa", p.principal_max_MPa}});
  j["cord_reaction"] = {{"Fx_N_per_mm", r.cord_reaction_N_mm.x()}, {"Fy_N_per_mm", r.cord_reaction_N_mm.y()},
                        {"moment_Nmm_per_mm", r.cord_moment_N}};
  j["mid_section"] = {{"N_N_per_mm", r.mid_section.force_N_mm.x()}, {"Q_N_per_mm", r.mid_section.force_N_mm.y()},
                      {"M_Nmm_per_mm", r.mid_section.moment_N}};
  const double B = scene.belt.width_mm;
  j["stiffness"] = {{"c_N_per_mm", r.c_N_per_mm}, {"EI_Nmm2_per_mm", r.EI_Nmm2_per_mm},
                    {"width_mm", B}, {"c_N", r.c_N_per_mm * B}, {"EI_Nmm2", r.EI_Nmm2_per_mm * B}};
  core::require_finite_json(j, "segment result");  // printed as JSON or text: no NaN/inf
  return j;
}

}  // namespace fitlib::scene
