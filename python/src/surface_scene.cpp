// Python bindings of surfaces (fit, eval, card grids), material points (update, drive, the
// thesis cases) and scenes (load, run, load cycle / accumulation / tension test as NumPy).
#include <algorithm>
#include <cmath>

#include <pybind11/complex.h>
#include <pybind11/eigen.h>

#include "bindings.hpp"
#include "fitlib/belt/accumulation.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/model/fritzson_cases.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/work_caps.hpp"
#include "fitlib/scene/planner.hpp"
#include "fitlib/scene/scene.hpp"
#include "fitlib/scene/writers.hpp"
#include "fitlib/surface/card_grid.hpp"
#include "fitlib/surface/fit.hpp"

namespace fitlib::python {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// ---- surfaces --------------------------------------------------------------------------------
// One value per point (rows of x).
py::array_t<double> surface_values(const surface::Surface& s, const RowMatrix& x, bool allow_extrapolation) {
  std::vector<double> out(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) out[i] = s.value(x.row(i).data(), allow_extrapolation);
  return to_array(out);
}

// Points as an (N, n) array; a 1-D array of n values is one point. TypeError naming `argument`
// for None, text or bools.
RowMatrix as_points(const surface::Surface& s, const Array& x, const char* argument) {
  auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(numbers(x.object, argument));
  const auto n = static_cast<Eigen::Index>(s.dimension());
  const bool one_point = a.ndim() <= 1;
  if (a.ndim() > 2 || (one_point ? a.size() : a.shape(1)) != n || a.size() == 0)
    throw core::UsageError("points must have " + std::to_string(n) + " coordinates (one per axis), one row a point");
  return Eigen::Map<const RowMatrix>(a.data(), one_point ? 1 : a.shape(0), n);
}

surface::AxisSpec axis_spec(const py::handle& h) {
  surface::AxisSpec a;
  if (py::isinstance<py::str>(h)) {
    a.name = h.cast<std::string>();
    return a;
  }
  const auto d = h.cast<py::dict>();
  a.name = d["name"].cast<std::string>();
  if (d.contains("unit")) a.unit = d["unit"].cast<std::string>();
  if (d.contains("transform")) a.transform = surface::parse_transform(d["transform"].cast<std::string>());
  if (d.contains("degree")) a.degree = d["degree"].cast<int>();
  return a;
}

// The measured points: arrays, or named columns of a CSV file (x the path, y the column).
surface::SampleSet samples(const py::object& x, const py::object& y, const surface::FitOptions& o) {
  if (py::isinstance<py::str>(x)) {
    std::vector<std::string> columns;
    for (const auto& a : o.axes) columns.push_back(a.name);
    return surface::read_sample_columns(x.cast<std::string>(), columns, y.cast<std::string>());
  }
  surface::SampleSet data;
  data.x = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(x).cast<RowMatrix>();
  const auto values = to_vector(y);
  data.y = Eigen::Map<const Eigen::VectorXd>(values.data(), values.size());
  data.source = "arrays";
  return data;
}

void bind_surface(py::module_& m) {
  using surface::Surface;
  py::class_<surface::Axis>(m, "SurfaceAxis", "An axis of a surface: name, unit, transform, degree, interval")
      .def_readonly("name", &surface::Axis::name)
      .def_readonly("unit", &surface::Axis::unit)
      .def_property_readonly("transform", [](const surface::Axis& a) { return std::string(surface::to_string(a.transform)); })
      .def_readonly("start", &surface::Axis::start)
      .def_readonly("end", &surface::Axis::end)
      .def_readonly("degree", &surface::Axis::degree)
      .def_readonly("levels", &surface::Axis::levels)
      .def_readonly("scattered", &surface::Axis::scattered);
  py::class_<Surface>(m, "Surface", "A Bezier tensor-product surface (formats.md §4)")
      .def_readonly("name", &Surface::name)
      .def_readonly("dependent_name", &Surface::dependent_name)
      .def_property_readonly("dependent_transform", [](const Surface& s) { return std::string(surface::to_string(s.dependent_transform)); })
      .def_readonly("axes", &Surface::axes)
      .def_readonly("control_points", &Surface::control_points)
      .def_property_readonly("statistics", [](const Surface& s) { return to_python(surface::surface_to_json(s)["statistics"]); })
      .def("to_json", [](const Surface& s) { return to_python(surface::surface_to_json(s)); })
      .def("save", [](const Surface& s, const std::string& path) { surface::save_surface(path, s); }, py::arg("path"))
      .def("__call__",
           [](const Surface& s, const Array& x, const Checked<bool>& allow) {
             return surface_values(s, as_points(s, x, "points"), allow.get("allow_extrapolation"));
           },
           py::arg("points"), py::arg("allow_extrapolation") = false,
           "Values at (N, n) points; InputError naming the axis outside its interval")
      .def("evaluate",
           [](const Surface& s, const Array& x, const Checked<bool>& allow) {
             const RowMatrix p = as_points(s, x, "point");
             const auto e = s.evaluate(p.row(0).data(), allow.get("allow_extrapolation"));
             return py::make_tuple(e.value, e.gradient, e.extrapolated);
           },
           py::arg("point"), py::arg("allow_extrapolation") = false, "(value, gradient, extrapolated) at one point")
      .def("contains", [](const Surface& s, const Array& x) {
        const RowMatrix p = as_points(s, x, "point");
        return s.contains(p.row(0).data());
      }, py::arg("point"));

  m.def("load_surface", &surface::load_surface, py::arg("path"), "Reads and validates a surface JSON (docs/surface.md); InputError names the file and key");
  m.def("surface_from_json",
        [](const py::object& j, const std::string& source) { return surface::surface_from_json(to_json(j), source); },
        py::arg("document"), py::arg("source") = "surface", "A surface from its JSON document (a dict), validated as load_surface");
  m.def("fit_surface",
        [](const py::object& x, const py::object& y, const py::list& axes, const std::string& dependent_name,
           const std::string& name, const std::string& missing, const Checked<double>& level_tolerance,
           const py::object& constraints, const std::string& dependent_transform) {
          surface::FitOptions o;
          for (const auto& a : axes) o.axes.push_back(axis_spec(a));
          o.dependent_name = dependent_name, o.name = name, o.level_tolerance = level_tolerance.get("level_tolerance");
          o.dependent_transform = surface::parse_transform(dependent_transform);
          // As fitcli: with user constraints the user takes charge of missing cells unless told.
          const char* remedy = constraints.is_none() ? "constrain" : "none";
          o.missing = surface::parse_missing_cell_remedy(!missing.empty() ? missing : remedy);
          if (!constraints.is_none()) o.user_constraints = to_json(constraints);
          return surface::fit_surface(samples(x, y, o), o);
        },
        py::arg("x"), py::arg("y"), py::arg("axes"), py::arg("dependent_name") = "y", py::arg("name") = "",
        py::arg("missing") = "", py::arg("level_tolerance") = 0.05, py::arg("constraints") = py::none(),
        py::arg("dependent_transform") = "linear",
        "Least-squares Bezier surface: x (N, n) and y (N) arrays, or x a CSV path and y its column name "
        "(errors then name file, line and column); axes: names or dicts {name, unit, transform, degree}; "
        "dependent_transform 'log10' fits log10 y (positive y; the surface still returns y)");
  m.def("read_samples",
        [](const std::string& path, const std::vector<std::string>& x_columns, const std::string& y_column) {
          const auto s = surface::read_sample_columns(path, x_columns, y_column);
          return py::make_tuple(RowMatrix(s.x), s.y);
        },
        py::arg("path"), py::arg("x_columns"), py::arg("y_column"), "(x, y) columns of a CSV with a header");

  m.def("card_grid",
        [](const card::Card& c, const Array& f, const OptionalArray& T, const OptionalArray& amp,
           const std::string& mode, const std::string& orientation) {
          surface::CardGridRequest r;
          r.mode = model::parse_test_mode(mode);
          r.orientation = orientation;
          r.frequency_Hz = to_vector(f.object, "frequency_Hz");
          if (!T.object.is_none()) r.temperature_C = to_vector(T.object, "temperature_C");
          if (!amp.object.is_none()) r.strain_amplitude = to_vector(amp.object, "strain_amplitude");
          return surface::evaluate_card_grid(c, r);
        },
        py::arg("card"), py::arg("frequency_Hz"), py::arg("temperature_C") = py::none(),
        py::arg("strain_amplitude") = py::none(), py::arg("mode") = "shear", py::arg("orientation") = "", "fitcli surface grid: the card's moduli over amplitudes x frequencies x temperatures (at most 1e6 points)");
  py::class_<surface::ModulusGrid>(m, "ModulusGrid", "A card over a grid (fitcli surface grid)")
      .def_property_readonly("columns", [](const surface::ModulusGrid& g) {
        std::vector<double> a, f, T, s, l, mean;
        for (const auto& r : g.rows)
          a.push_back(r.strain_amplitude), f.push_back(r.frequency_Hz), T.push_back(r.temperature_C),
              s.push_back(r.storage_MPa), l.push_back(r.loss_MPa), mean.push_back(r.mean_modulus_MPa);
        py::dict d;
        d["strain_amplitude"] = to_array(a), d["frequency_Hz"] = to_array(f), d["temperature_C"] = to_array(T);
        d["storage_MPa"] = to_array(s), d["loss_MPa"] = to_array(l), d["mean_modulus_MPa"] = to_array(mean);
        return d;
      })
      .def("to_csv", &surface::modulus_grid_csv)
      .def("surface",
           [](const surface::ModulusGrid& g, const std::string& quantity, const std::vector<int>& degrees) {
             return surface::surface_from_grid(g, quantity, degrees);
           },
           py::arg("quantity") = "storage", py::arg("degrees") = std::vector<int>{});
}

// ---- material points -------------------------------------------------------------------------
model::DriveControl control(const py::handle& h) {
  model::DriveControl c;
  if (h.is_none()) return c;  // traction-free
  const auto t = h.cast<py::sequence>();
  if (t.size() != 2) throw core::UsageError("a drive component is ('strain' | 'stress', values)");
  const auto kind = t[0].cast<std::string>();
  if (kind != "strain" && kind != "stress") throw core::UsageError("a drive component is ('strain' | 'stress', values)");
  c.imposed = kind == "strain" ? model::DriveControl::Imposed::strain : model::DriveControl::Imposed::stress;
  c.values = to_vector(t[1]);
  return c;
}

py::dict drive_dict(const model::DriveResult& r) {
  RowMatrix strain(r.time_s.size(), 6), stress(r.time_s.size(), 6);
  for (std::size_t n = 0; n < r.time_s.size(); ++n) strain.row(n) = r.strain[n], stress.row(n) = r.stress[n];
  py::dict d;
  d["time_s"] = to_array(r.time_s), d["strain"] = strain, d["stress_MPa"] = stress;
  d["final_state"] = to_array(r.final_state);
  return d;
}

void bind_material_point(py::module_& m) {
  using model::MaterialPoint;
  py::class_<MaterialPoint, std::shared_ptr<MaterialPoint>>(m, "MaterialPoint",
                                                            "What an FE code drives (docs/model.md); Voigt 11 22 33 23 13 12")
      .def("describe", &MaterialPoint::describe)
      .def_property_readonly("state_size", &MaterialPoint::state_size)
      .def("initial_state", [](const MaterialPoint& p) { return to_array(p.initial_state()); })
      .def("update",
           [](const MaterialPoint& p, const Array& state, const model::Vector6& strain, const Checked<double>& dt,
              const Checked<std::optional<double>>& temperature_C) {
             const auto s = to_vector(state.object, "state");
             const double dt_s = dt.get("dt_s"), T = optional_temperature(temperature_C);
             if (s.size() != p.state_size()) throw core::UsageError("state has the wrong size");
             // The C++ contract takes finite input from the FE code; here it comes from a user.
             if (!strain.allFinite()) throw core::UsageError("update: the strain is not finite");
             if (!std::all_of(s.begin(), s.end(), [](double v) { return std::isfinite(v); }))
               throw core::UsageError("update: the state is not finite");
             model::require_temperature("update", T);
             std::vector<double> next(p.state_size());
             model::Matrix6 tangent;
             const model::Vector6 sigma = p.update(s.data(), strain, dt_s, T, next.data(), &tangent);
             return py::make_tuple(sigma, to_array(next), tangent);
           },
           py::arg("state"), py::arg("strain"), py::arg("dt_s"), py::arg("temperature_C") = py::none(),
           "(stress, next state, tangent) of one increment to the total strain")
      .def("complex_stiffness",
           [](const MaterialPoint& p, const Checked<double>& f, const Checked<std::optional<double>>& temperature_C) {
             const double frequency_Hz = f.get("frequency_Hz"), T = optional_temperature(temperature_C);
             model::require_steady_condition("complex_stiffness", frequency_Hz, T);
             return p.complex_stiffness(frequency_Hz, T);
           },
           py::arg("frequency_Hz"), py::arg("temperature_C") = py::none());

  m.def("make_material_point",
        [](const std::shared_ptr<model::Model>& model, const Array& values, const std::string& fidelity,
           const Checked<double>& frequency_Hz, const Checked<std::optional<double>>& temperature_C,
           const Checked<double>& bulk_modulus_MPa, const OptionalArray& damage_driver_hold) {
          if (fidelity != "viscoelastic" && fidelity != "elastic")
            throw core::UsageError("fidelity must be viscoelastic or elastic, not '" + fidelity + "'");
          model::PointOptions o;
          o.fidelity = fidelity == "elastic" ? core::Fidelity::elastic
                                             : core::Fidelity::complete;
          o.frequency_Hz = frequency_Hz.get("frequency_Hz"), o.temperature_C = optional_temperature(temperature_C);
          o.bulk_modulus_MPa = bulk_modulus_MPa.get("bulk_modulus_MPa");
          if (!damage_driver_hold.object.is_none())
            o.damage_driver_hold = to_vector(damage_driver_hold.object, "damage_driver_hold");
          return std::const_pointer_cast<MaterialPoint>(model::make_material_point(*model, to_vector(values.object, "values"), o));
        },
        py::arg("model"), py::arg("values"), py::arg("fidelity") = "viscoelastic", py::arg("frequency_Hz") = 1.0,
        py::arg("temperature_C") = py::none(), py::arg("bulk_modulus_MPa") = std::nan(""),
        py::arg("damage_driver_hold") = py::none(),
        "damage_driver_hold: a damage model's drivers held beyond these (a card's fit.data_window.damage_driver, "
        "as the segment's complete level does); None = the damage law at every amplitude");
  m.def("drive",
        [](const MaterialPoint& p, const Array& time_s, const py::sequence& components, const OptionalArray& T) {
          model::DriveProgram program;
          program.time_s = to_vector(time_s.object, "time_s");
          if (components.size() != 6) throw core::UsageError("drive needs 6 components (None = traction-free)");
          bool stress_controlled = false;
          for (int i = 0; i < 6; ++i) {
            program.components[i] = control(components[i]);
            stress_controlled |= program.components[i].imposed == model::DriveControl::Imposed::stress;
          }
          model::check_point_work(model::point_work(p.state_size(), static_cast<double>(program.time_s.size()),
                                                    stress_controlled),
                                  p.describe(), "len(time_s)");
          if (!T.object.is_none()) program.temperature_C = to_vector(T.object, "temperature_C");
          return drive_dict(model::drive(p, program));
        },
        py::arg("point"), py::arg("time_s"), py::arg("components"), py::arg("temperature_C") = py::none(),
        "Each Voigt component None (σ = 0) or ('strain' | 'stress', values per time)");
  m.def("drive_test",
        [](const MaterialPoint& p, const std::string& mode, const std::string& orientation, const Checked<double>& a,
           const Checked<double>& mean, const Checked<double>& f, const Checked<int>& n, const Checked<int>& steps,
           const Checked<std::optional<double>>& temperature_C) {
          const double frequency_Hz = f.get("frequency_Hz"), T = optional_temperature(temperature_C);
          const double amplitude = a.get("amplitude"), mean_strain = mean.get("mean_strain");
          const int cycles = n.get("cycles"), steps_per_cycle = steps.get("steps_per_cycle");
          // fitcli material-point's option ranges and work cap
          require_in("amplitude", amplitude, 0.0, 10.0);
          require_in("mean_strain", mean_strain, -10.0, 10.0);
          require_in("frequency_Hz", frequency_Hz, 1e-100, 1e100);
          if (!std::isnan(T)) require_in("temperature_C", T, -273.15, 1000.0);
          require_in("cycles", cycles, 1, 1e6);
          require_in("steps_per_cycle", steps_per_cycle, 4, 1e6);
          model::TestCondition c;
          c.mode = model::parse_test_mode(mode), c.orientation = orientation, c.temperature_C = T;
          model::check_point_work(model::point_work(p.state_size(), double(cycles) * steps_per_cycle, c.mode),
                                  p.describe(), "cycles x steps_per_cycle");
          const auto h = model::fritzson::cyclic_history(amplitude, mean_strain, frequency_Hz, cycles, steps_per_cycle);
          const auto r = model::drive(p, model::test_program(c, h));
          auto d = drive_dict(r);
          d["test_strain"] = to_array(h.strain), d["test_stress_MPa"] = to_array(model::test_stress(r, c));
          return d;
        },
        py::arg("point"), py::arg("mode") = "shear", py::arg("orientation") = "", py::arg("amplitude") = 0.01,
        py::arg("mean_strain") = 0.0, py::arg("frequency_Hz") = 1.0, py::arg("cycles") = 5,
        py::arg("steps_per_cycle") = 200, py::arg("temperature_C") = py::none(),
        "fitcli material-point: ε(t) = mean − a cos 2πft in the test's program");
  m.def("fritzson_thesis_case",
        [](const card::Card& c, const std::string& id, const Checked<int>& steps) {
          const int steps_per_cycle = steps.get("steps_per_cycle");
          require_in("steps_per_cycle", steps_per_cycle, 4, 1e6);  // fitcli's range and work cap
          const model::fritzson::MaterialPoint point = model::fritzson::thesis_point(*c.model(), c.values());
          const auto& tc = model::fritzson::thesis_case(id);
          model::fritzson::check_thesis_case_work(*c.model(), c.values(), tc, steps_per_cycle, "steps_per_cycle");
          const auto loops = model::fritzson::run_thesis_case(point, tc, steps_per_cycle);
          py::dict d;
          d["time_s"] = to_array(loops.time_s), d["displacement"] = to_array(loops.displacement);
          d["strain"] = to_array(loops.strain), d["stress_MPa"] = to_array(loops.stress_MPa);
          d["nominal_MPa"] = to_array(loops.nominal_MPa);
          return d;
        },
        py::arg("card"), py::arg("case"), py::arg("steps_per_cycle") = 200,
        "fitcli material-point --case: a Report II §7.2 case (7.1–7.5) of a fritzson card");
}

// ---- scenes ----------------------------------------------------------------------------------
py::dict load_cycle_columns(const scene::SceneResult& r) {
  const auto& samples = r.cycle->samples;
  std::vector<double> s, t, F, K, p, gamma, slide, mu;
  std::vector<std::string> pulley, zone;
  for (const auto& x : samples) {
    s.push_back(x.s_mm), t.push_back(x.t_s), F.push_back(x.F_N), K.push_back(x.K_1_mm), p.push_back(x.p_MPa);
    gamma.push_back(x.gamma_rad), slide.push_back(x.slide_mm_s), mu.push_back(x.friction_used);
    pulley.push_back(r.drive->geometry.pulleys[x.pulley].name), zone.push_back(belt::to_string(x.zone));
  }
  py::dict d;
  d["s_mm"] = to_array(s), d["t_s"] = to_array(t), d["F_N"] = to_array(F), d["K_1_per_mm"] = to_array(K);
  d["p_MPa"] = to_array(p), d["gamma_rad"] = to_array(gamma), d["sliding_velocity_mm_s"] = to_array(slide);
  d["friction_used"] = to_array(mu);
  d["pulley"] = py::module_::import("numpy").attr("array")(pulley);
  d["zone"] = py::module_::import("numpy").attr("array")(zone);
  return d;
}

py::dict accumulation_dict(const scene::AccumulationMap& a) {
  py::dict d;
  d["kappa"] = a.kappa, d["shear_stress_MPa"] = a.shear_stress_MPa, d["spectrum"] = a.spectrum_source;
  d["omega_rad_s"] = to_array(a.omega_rad_s);
  d["cycles"] = to_array(std::vector<double>(a.cycles.begin(), a.cycles.end()));
  d["gamma"] = to_array(a.gamma).attr("reshape")(a.omega_rad_s.size(), a.cycles.size());
  d["critical_cycles"] = to_array(std::vector<double>(a.critical_cycles.begin(), a.critical_cycles.end()));
  return d;
}

py::dict tension_phase(const std::vector<belt::TensionTestPoint>& pts) {
  std::vector<double> t, d, T, b;
  for (const auto& q : pts)
    t.push_back(q.t_s), d.push_back(q.elongation_mm), T.push_back(q.span_tension_N), b.push_back(q.boundary_rad);
  py::dict out;
  out["t_s"] = to_array(t), out["elongation_mm"] = to_array(d), out["span_tension_N"] = to_array(T);
  out["boundary_rad"] = to_array(b);
  return out;
}

void bind_scene(py::module_& m) {
  using scene::Scene;
  using scene::SceneResult;
  py::class_<Scene>(m, "Scene", "A drive scene (formats.md §5)")
      .def_readonly("name", &Scene::name)
      .def_readonly("path", &Scene::path)
      .def_readonly("temperature_C", &Scene::temperature_C)
      .def_readonly("friction", &Scene::friction)
      .def_readonly("effects", &Scene::effects)
      .def_readonly("outputs", &Scene::outputs)
      .def_readonly("materials", &Scene::materials)
      .def("run", [](const Scene& s) { return scene::run_scene(s); }, "Runs the planner (fitcli belt)");
  py::class_<scene::EffectReport>(m, "EffectReport", "One effect of a scene run: name, ran, wall_s, reason")
      .def_readonly("name", &scene::EffectReport::name)
      .def_readonly("ran", &scene::EffectReport::ran)
      .def_readonly("wall_s", &scene::EffectReport::wall_s)
      .def_readonly("reason", &scene::EffectReport::reason);
  py::class_<SceneResult>(m, "SceneResult", "What a scene run computed: effects, load cycle, life, warnings (None for what did not run)")
      .def_property_readonly("effects", [](const SceneResult& r) { return r.plan.effects; })
      .def_property_readonly("unavailable_outputs", [](const SceneResult& r) { return r.plan.unavailable_outputs; })
      .def_readonly("warnings", &SceneResult::warnings,
                    "Inputs used beyond what they vouch for (a card outside its data window, a life below 1000 cycles)")
      .def_property_readonly("load_cycle",
                             [](const SceneResult& r) { return r.cycle ? py::object(load_cycle_columns(r)) : py::none(); },
                             "Samples along the path as NumPy columns (None when not run)")
      .def_property_readonly("accumulation", [](const SceneResult& r) {
        return r.accumulation ? py::object(accumulation_dict(*r.accumulation)) : py::none();
      })
      .def_property_readonly("tension_test", [](const SceneResult& r) {
        if (!r.tension_test) return py::object(py::none());
        py::dict d;
        d["loading"] = tension_phase(r.tension_test->result.loading), d["unloading"] = tension_phase(r.tension_test->result.unloading);
        return py::object(d);
      })
      .def_property_readonly("life", &life_dict, "Lives per mode, governing mode, design points (None when not run)")
      .def_readonly("total_wall_s", &SceneResult::total_wall_s)
      .def("load_history_csv", &scene::load_history_csv);

  m.def("load_scene", &scene::load_scene, py::arg("path"), "Reads and validates a scene TOML (formats.md §5)");
  m.def("parse_scene", &scene::parse_scene, py::arg("toml_text"), py::arg("source_name") = "scene", "A scene from TOML text; source_name names it in errors (relative card paths from the current folder)");
  m.def("run_scene", [](const Scene& s) { return scene::run_scene(s); }, py::arg("scene"), "Runs the effects the scene asks for (fitcli belt): a SceneResult");
  m.def("scene_summary", [](const Scene& s, const SceneResult& r) { return to_python(scene::summary_json(s, r)); },
        py::arg("scene"), py::arg("result"), "The summary.json document of fitcli belt");
  m.def("write_scene_outputs",
        [](const Scene& s, const SceneResult& r, const std::string& folder, const Checked<bool>& record_timing) {
          return scene::write_outputs(s, r, folder, record_timing.get("record_timing"));
        },
        py::arg("scene"), py::arg("result"), py::arg("folder"),
        py::arg("record_timing") = false, "Writes the scene's outputs (load_history.csv, summary.json, ...) into a folder, as fitcli belt");
  m.def("accumulation_map",
        [](const std::string& spectrum, const Checked<double>& stress, const Checked<long>& n,
           const Checked<int>& n_cycle, const Checked<double>& w_min, const Checked<double>& w_max,
           const Checked<int>& n_omega, const Checked<double>& k, const Checked<double>& limit) {
          const double omega_min = w_min.get("omega_min"), omega_max = w_max.get("omega_max");
          const double shear_stress_MPa = stress.get("shear_stress_MPa"), kappa = k.get("kappa");
          const double strain_limit = limit.get("strain_limit");
          const long cycles = n.get("cycles");
          const int cycle_points = n_cycle.get("cycle_points"), omega_points = n_omega.get("omega_points");
          // fitcli accumulate's option ranges and work cap
          require_in("shear_stress_MPa", shear_stress_MPa, 1e-300, 1e100);
          require_in("cycles", static_cast<double>(cycles), 1, 1e12);
          require_in("cycle_points", cycle_points, 1, scene::kMaxAccumulationPoints);
          require_in("omega_points", omega_points, 1, scene::kMaxAccumulationPoints);
          require_in("omega_min", omega_min, 1e-300, 1e100);
          require_in("omega_max", omega_max, omega_min, 1e100);
          require_in("kappa", kappa, 0.0, 1e100);
          if (static_cast<double>(cycle_points) * omega_points > scene::kMaxAccumulationWork)
            throw core::UsageError("cycle_points x omega_points exceeds the work cap " +
                                   core::format_number(scene::kMaxAccumulationWork) + " (README, work caps)");
          scene::AccumulationSpec spec;
          spec.spectrum = spectrum, spec.shear_stress_MPa = shear_stress_MPa, spec.cycles = cycles;
          spec.cycle_points = cycle_points, spec.omega_min_rad_s = omega_min, spec.omega_max_rad_s = omega_max;
          spec.omega_points = omega_points;
          if (strain_limit > 0) spec.strain_limit = strain_limit;
          std::string source;
          const auto s = scene::scene_spectrum(Scene{}, spectrum, &source);
          auto map = scene::accumulation_map(s, spec, kappa);
          map.spectrum_source = source;
          return accumulation_dict(map);
        },
        py::arg("spectrum"), py::arg("shear_stress_MPa") = 1.0, py::arg("cycles") = 10000, py::arg("cycle_points") = 50,
        py::arg("omega_min") = 1.0, py::arg("omega_max") = 1e4, py::arg("omega_points") = 100,
        py::arg("kappa") = 3.141592653589793, py::arg("strain_limit") = -1.0,
        "fitcli accumulate --spectrum SHAPE: Γ(N, ω) of a spectrum shape");
}

}  // namespace

void bind_surface_point_scene(py::module_& m) {
  bind_surface(m);
  bind_material_point(m);
  bind_scene(m);
}

}  // namespace fitlib::python
