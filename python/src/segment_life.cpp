// The Python module: the segment's static load case (fitcli segment) with its stresses as NumPy
// arrays, and a scene's fatigue life (fitcli life): lives per mode, governing mode, design
// points. A thin layer over scene/segment_case.hpp, scene/planner.hpp and scene/writers.hpp
// (docs/python.md).
#include <cmath>

#include "bindings.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/fatigue/card.hpp"
#include "fitlib/fatigue/life_fit.hpp"
#include "fitlib/scene/life_tests.hpp"
#include "fitlib/scene/output_paths.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/scene/segment_case.hpp"
#include "fitlib/scene/writers.hpp"

namespace fitlib::python {
namespace {

// Infinite lives (no significant peak) cross as Python's inf, as the library holds them.
py::dict mode_life_dict(const fatigue::ModeLife& l) {
  py::dict d;
  d["mode"] = std::string(fatigue::to_string(l.mode));
  d["design_point"] = l.design_point, d["x_mm"] = l.x_mm, d["y_mm"] = l.y_mm;
  d["life_cycles"] = l.life_cycles, d["life_h"] = l.life_h;
  d["sum_terms"] = l.sum_terms, d["temperature_factor"] = l.temperature_factor;
  std::vector<double> peak_t, peak_stress;
  std::vector<std::string> peak_pulley;
  for (const auto& p : l.peaks) peak_t.push_back(p.t_s), peak_stress.push_back(p.stress_MPa), peak_pulley.push_back(p.pulley);
  d["peak_t_s"] = to_array(peak_t), d["peak_stress_MPa"] = to_array(peak_stress), d["peak_pulley"] = peak_pulley;
  py::dict shares;
  for (const auto& s : l.shares) shares[py::str(s.name)] = s.damage_per_cycle;
  d["damage_per_cycle"] = shares;
  d["t_s"] = to_array(l.t_s), d["effective_stress_MPa"] = to_array(l.effective_stress_MPa);
  return d;
}

}  // namespace

py::object life_dict(const scene::SceneResult& r) {
  if (!r.life) return py::none();
  const auto& report = r.life->report;
  py::dict d;
  d["fidelity"] = core::to_string(r.life->plan.fidelity), d["reason"] = r.life->plan.reason;
  d["governing"] = report.governing, d["life_cycles"] = report.life_cycles, d["life_h"] = report.life_h;
  py::dict modes;
  for (const auto& m : report.modes) modes[py::str(fatigue::to_string(m.mode))] = mode_life_dict(m);
  d["modes"] = modes;
  if (report.cord_break) {
    py::dict c;
    c["mean_MPa"] = report.cord_break->mean_MPa, c["amplitude_MPa"] = report.cord_break->amplitude_MPa;
    c["equivalent_amplitude_MPa"] = report.cord_break->equivalent_amplitude_MPa;
    c["life_cycles"] = report.cord_break->life_cycles, c["life_h"] = report.cord_break->life_h;
    d["cord_break"] = c;
  } else {
    d["cord_break"] = py::none();
  }
  py::list inputs;
  for (const auto& f : r.life->inputs) {
    py::dict i;
    i["role"] = f.role, i["path"] = f.path, i["sha256"] = f.sha256, i["used_for"] = f.used_for;
    inputs.append(i);
  }
  d["inputs"] = inputs;
  return d;
}

namespace {

py::dict segment_dict(const segment::StaticResult& r) {
  py::dict d;
  std::vector<std::string> names;
  std::vector<double> x, y, s11, s22, s12, s33, smax;
  for (const auto& p : r.stresses) {
    names.push_back(p.point.name), x.push_back(p.point.x_mm), y.push_back(p.point.y_mm);
    s11.push_back(p.sigma11_MPa), s22.push_back(p.sigma22_MPa), s12.push_back(p.sigma12_MPa);
    s33.push_back(p.sigma33_MPa), smax.push_back(p.principal_max_MPa);
  }
  d["points"] = names, d["x_mm"] = to_array(x), d["y_mm"] = to_array(y);
  d["sigma11_radial_MPa"] = to_array(s11), d["sigma22_longitudinal_MPa"] = to_array(s22);
  d["sigma12_MPa"] = to_array(s12), d["sigma33_MPa"] = to_array(s33), d["principal_max_MPa"] = to_array(smax);
  d["cord_reaction_N_per_mm"] = to_array({r.cord_reaction_N_mm.x(), r.cord_reaction_N_mm.y()});
  d["cord_moment_Nmm_per_mm"] = r.cord_moment_N;
  d["mid_section_N_per_mm"] = to_array({r.mid_section.force_N_mm.x(), r.mid_section.force_N_mm.y()});
  d["mid_section_M_Nmm_per_mm"] = r.mid_section.moment_N;
  d["c_N_per_mm"] = r.c_N_per_mm, d["EI_Nmm2_per_mm"] = r.EI_Nmm2_per_mm;
  d["elements"] = r.elements, d["nodes"] = r.nodes, d["equations"] = r.equations;
  d["increments"] = r.increments, d["newton_iterations"] = r.newton_iterations, d["wall_s"] = r.wall_s;
  return d;
}

// The scene's [segment] case, its load replaced where an argument is given.
py::dict run_segment(scene::Scene s, const Checked<std::optional<double>>& strain,
                     const Checked<std::optional<double>>& curvature, const Checked<std::optional<double>>& pressure,
                     const std::string& vtk_path) {
  // the arguments' types before the scene's (a wrong type is the call's mistake, whatever the scene)
  const auto strain_given = strain.get("strain"), curvature_1_mm = curvature.get("curvature_1_mm");
  const auto pressure_MPa = pressure.get("pressure_MPa");
  if (!s.segment) throw core::InputError("the scene has no [segment] table", s.path, 0, 0, "segment");
  // As fitcli segment --vtk: a file (not stdout), never the scene or a card it names (UsageError),
  // in a folder that exists and can be written (InputError, checked by run_segment_case before
  // the FE), written through a temporary and a rename.
  if (vtk_path == "-") throw core::UsageError("vtk_path needs a file (- would be stdout)");
  scene::refuse_outputs_on_inputs(s, {{"vtk_path", vtk_path}});
  if (strain_given) s.segment->load.strain = *strain_given;
  if (curvature_1_mm) s.segment->load.curvature_1_mm = *curvature_1_mm;
  if (pressure_MPa) s.segment->load.pressure_MPa = *pressure_MPa;
  const auto c = scene::run_segment_case(s, vtk_path);
  py::dict d = segment_dict(c.result);
  d["summary"] = to_python(scene::segment_json(s, c));
  return d;
}

// A result whose life ran (life_json and life_text read it; of scene.run() without [outputs] life
// they raised a raw "bad optional access").
const scene::SceneResult& with_life(const scene::SceneResult& r) {
  if (!r.life) throw core::UsageError("result: no life was computed (run the scene with run_life, or ask for [outputs] life)");
  return r;
}

// fitcli life-fit: the card, its warnings, each mode's fit, and the cases with their observed and
// predicted lives (arrays) under the fitted card.
py::dict fit_life_constants(const std::string& observed, const std::string& start, const Checked<bool>& fix_n,
                            const Checked<bool>& fix_b) {
  const fatigue::HeldConstants held{fix_n.get("fix_n"), fix_b.get("fix_b")};
  const auto r = scene::fit_life_tests(core::read_file(observed), observed, start, held);
  py::dict d;
  d["card"] = to_python(fatigue::card_to_json(r.fit.card));
  d["warnings"] = r.fit.warnings;
  py::list fits;
  for (const auto& f : r.fit.fits) {
    nlohmann::json j = fatigue::life_fit_json(f);
    j["mode"] = fatigue::to_string(f.mode);
    fits.append(to_python(j));
  }
  d["fits"] = fits;
  std::vector<std::string> names, modes;
  std::vector<double> temperature, observed_cycles, predicted_cycles;
  std::vector<bool> runout;
  for (const auto& c : r.cases) {
    names.push_back(c.name), modes.push_back(fatigue::to_string(c.mode)), runout.push_back(c.runout);
    temperature.push_back(c.temperature_C), observed_cycles.push_back(c.observed_cycles);
    predicted_cycles.push_back(std::pow(
        10.0, fatigue::predicted_log10_life(c, r.fit.card.law(c.mode), r.fit.card.reference_temperature_C)));
  }
  d["cases"] = names, d["failure_mode"] = modes, d["runout"] = runout, d["temperature_C"] = to_array(temperature);
  d["observed_cycles"] = to_array(observed_cycles), d["predicted_cycles"] = to_array(predicted_cycles);
  return d;
}

}  // namespace

void bind_segment_life(py::module_& m) {
  m.def("fit_life_constants", &fit_life_constants, py::arg("observed"), py::arg("start") = "",
        py::arg("fix_n") = false, py::arg("fix_b") = false,
        "fitcli life-fit: the life constants per failure mode fitted to observed lives (a life-test list of scenes, "
        "or stored peaks); dict: card (the fatigue card), warnings, fits, cases with observed and predicted cycles "
        "(runout: the test stopped without failing; failure_mode then names the mode whose points it bounds)");
  m.def("segment_case", &run_segment, py::arg("scene"), py::arg("strain") = py::none(),
        py::arg("curvature_1_mm") = py::none(), py::arg("pressure_MPa") = py::none(), py::arg("vtk_path") = "",
        "fitcli segment: the scene's static [segment] case (load overridable); stresses at the points as arrays, "
        "'summary' the --json document. vtk_path (fitcli's --vtk): the mesh with displacements and cell stresses, "
        "written through a temporary and a rename; UsageError when it is '-', the scene file or a card the scene "
        "names, InputError when its folder is missing or not writable (both before the FE runs)");
  m.def("run_life", &scene::run_life, py::arg("scene"),
        "fitcli life: runs the scene with the life asked for; SceneResult.life holds it");
  m.def("run_life", [](const std::string& path) { return scene::run_life(scene::load_scene(path)); },
        py::arg("scene_path"), "fitcli life --scene PATH: the scene file read and run with the life asked for");
  m.def("life_json",
        [](const scene::Scene& s, const scene::SceneResult& r, const Checked<bool>& record_timing) {
          const bool wall_times = record_timing.get("record_timing");
          return to_python(scene::life_json(s, with_life(r), wall_times));
        },
        py::arg("scene"), py::arg("result"), py::arg("record_timing") = false, "The life.json document");
  m.def("life_text", [](const scene::Scene& s, const scene::SceneResult& r) { return scene::life_text(s, with_life(r)); },
        py::arg("scene"), py::arg("result"), "The table fitcli life prints");
}

}  // namespace fitlib::python
