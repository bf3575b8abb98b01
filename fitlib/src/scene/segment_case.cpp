#include "fitlib/scene/segment_case.hpp"

#include "fitlib/core/error.hpp"
#include "fitlib/core/finite_output.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/scene/planner.hpp"
#include "effects.hpp"

namespace fitlib::scene {

namespace {

// The load frequency at which the cards give their elastic equivalents.
double case_frequency_Hz(const Scene& scene) {
  if (scene.segment->frequency_Hz) return *scene.segment->frequency_Hz;
  if (scene.pulleys.size() < 2)
    throw core::InputError("the cards of [belt.materials] give their storage stiffness at a load frequency: set "
                           "[segment] frequency_Hz (the scene has no drive to take it from)",
                           scene.path, 0, 0, "segment.frequency_Hz");
  return detail::load_frequency_Hz(make_drive(scene, resolve_stiffness(scene)));
}

}  // namespace

SegmentCase run_segment_case(const Scene& scene, const std::string& vtk_path) {
  if (!scene.segment) throw core::InputError("the scene has no [segment] table", scene.path, 0, 0, "segment");
  if (!vtk_path.empty()) core::check_output_path(vtk_path);  // before the FE, not after it
  SegmentCase out;
  segment::StaticSetup setup = scene.segment->setup;
  out.temperature_C = scene.temperature_C;
  const auto& roles = detail::kSegmentRoles;
  for (int k = 0; k < 2; ++k) {
    if (!scene.materials.count(roles[k])) {
      const segment::IsotropicElastic& e = setup.materials[k];
      out.materials.push_back({roles[k], "[segment.materials]",
                               "E " + core::format_number(e.E_MPa) + " MPa, nu " + core::format_number(e.nu)});
      continue;
    }
    if (out.frequency_Hz == 0.0) out.frequency_Hz = case_frequency_Hz(scene);
    segment::RoleMaterialOptions options;
    options.fidelity = core::Fidelity::elastic;
    options.temperature_C = scene.temperature_C, options.frequency_Hz = out.frequency_Hz;
    setup.material_points[k] = detail::card_point(scene, roles[k], options, out.warnings);
    out.materials.push_back({roles[k], scene.materials.at(roles[k]), setup.material_points[k]->describe()});
  }
  segment::StaticSolution solution;
  segment::Mesh mesh;
  out.result = segment::run_static_case(setup, scene.segment->load, &solution, &mesh);
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
  return out;
}

nlohmann::json segment_json(const Scene& scene, const SegmentCase& c) {
  const segment::StaticResult& r = c.result;
  const auto& load = scene.segment->load;
  nlohmann::json j;
  j["scene"] = scene.name;
  for (const SegmentMaterial& m : c.materials)
    j["materials"].push_back({{"role", m.role}, {"source", m.source}, {"material", m.material}});
  if (c.frequency_Hz > 0.0) j["cards_read_at"] = {{"temperature_C", c.temperature_C}, {"frequency_Hz", c.frequency_Hz}};
  if (!c.warnings.empty()) j["warnings"] = c.warnings;
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
