// The Python module `fitlib._fitlib` (docs/python.md): errors, JSON and array helpers,
// dynamic-test tables and models. A thin layer over the public headers: every function calls the
// library and converts its arguments and results, nothing more.
#include <cmath>
#include <limits>

#include "bindings.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/eplexor.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/model/material_point.hpp"
#include "fitlib/model/model.hpp"
#include "fitlib/surface/card_grid.hpp"

namespace fitlib::python {

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

nlohmann::json to_json(const py::handle& object) {
  if (object.is_none()) return nlohmann::json::object();
  const auto text = py::module_::import("json").attr("dumps")(object).cast<std::string>();
  return nlohmann::json::parse(text);
}

py::array_t<double> to_array(const std::vector<double>& v) {
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
}

std::vector<double> to_vector(const py::handle& object, const char* argument) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(numbers(object, argument));
  return std::vector<double>(a.data(), a.data() + a.size());
}

// ---- errors: one Python class per fitlib error class, all derived from FitlibError ----------
void bind_errors(py::module_& m) {
  static py::exception<std::exception> base(m, "FitlibError");
  static py::exception<core::InputError> input(m, "InputError", base.ptr());
  static py::exception<core::UsageError> usage(m, "UsageError", base.ptr());
  static py::exception<core::NumericalError> numerical(m, "NumericalError", base.ptr());
  for (py::handle error : std::initializer_list<py::handle>{base, input, usage, numerical})
    error.attr("__module__") = "fitlib";
  base.attr("__doc__") = "Any error of fitlib; exit_code is fitcli's exit code for it (docs/python.md)";
  input.attr("__doc__") = "Bad input (fitcli exit 3): file, line, column and key name where it is; detail the reason";
  usage.attr("__doc__") = "Misuse: an argument out of its range or options that conflict (fitcli exit 2)";
  numerical.attr("__doc__") = "A solver failed or a result would not be finite (fitcli exit 4)";
  base.attr("exit_code") = int(core::kNumericalFailure);
  input.attr("exit_code") = int(core::kBadInput);
  usage.attr("exit_code") = int(core::kUsageError);
  numerical.attr("exit_code") = int(core::kNumericalFailure);
  for (const char* name : {"file", "key", "detail"}) input.attr(name) = py::str("");
  for (const char* name : {"line", "column"}) input.attr(name) = 0;
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const core::InputError& e) {
      py::object error = py::reinterpret_borrow<py::object>(input.ptr())(e.what());
      error.attr("file") = e.file();
      error.attr("line") = e.line();
      error.attr("column") = e.column();
      error.attr("key") = e.key();
      error.attr("detail") = e.detail();
      PyErr_SetObject(input.ptr(), error.ptr());
    } catch (const core::UsageError& e) {
      usage(e.what());
    } catch (const core::NumericalError& e) {
      numerical(e.what());
    }
  });
}

namespace {

// ---- broadcasting of condition arrays (NumPy rules) -----------------------------------------
struct Broadcast {
  std::vector<py::ssize_t> shape;
  std::vector<std::vector<double>> columns;  // one flat column per argument
};

// max_points > 0: the work cap of an evaluation (issue 37 audit: card.eval over two broadcast
// arrays of 10^4 values made 10^8 points and ran on); the cap of card_grid and fitcli surface grid,
// checked on the broadcast shape before any column is made.
using Named = std::vector<std::pair<const char*, py::object>>;  // argument name, value

Broadcast broadcast(const Named& arguments, double max_points = 0.0) {
  py::list arrays;
  for (const auto& [name, a] : arguments) arrays.append(numbers(a, name));  // None, "abc": TypeError naming it
  const py::list out = py::module_::import("numpy").attr("broadcast_arrays")(*arrays);
  Broadcast b;
  const auto first = out[0].cast<py::array>();
  if (max_points > 0.0 && static_cast<double>(first.size()) > max_points)
    throw core::InputError("the arguments broadcast to " + core::format_number(static_cast<double>(first.size())) +
                               " points, above the work cap " + core::format_number(max_points) +
                               " points (README, work caps; as card_grid); split the call",
                           "", 0, 0, "points");
  b.shape.assign(first.shape(), first.shape() + first.ndim());
  for (std::size_t k = 0; k < out.size(); ++k)
    b.columns.push_back(to_vector(py::module_::import("numpy").attr("ascontiguousarray")(out[k]), arguments[k].first));
  return b;
}

py::array_t<double> shaped(const std::vector<double>& v, const std::vector<py::ssize_t>& shape) {
  return to_array(v).attr("reshape")(py::tuple(py::cast(shape)));
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

py::object or_nan(const py::object& temperature_C) {
  return temperature_C.is_none() ? py::object(py::float_(kNaN)) : temperature_C;
}

model::TestMode mode_or_native(const model::Model& m, const std::string& mode) {
  return mode.empty() ? m.native_mode() : model::parse_test_mode(mode);
}

std::vector<double> checked_values(const model::Model& m, const Array& p) {
  auto v = to_vector(p.object, "p");
  if (v.size() != m.size())
    throw core::UsageError(m.kind() + " has " + std::to_string(m.size()) + " parameters, got " +
                           std::to_string(v.size()));
  model::require_finite_parameters(m, v);
  return v;
}

}  // namespace

// Moduli over broadcast arrays of frequency, temperature and amplitude.
py::dict moduli_arrays(const model::Model& m, const std::vector<double>& p, const py::object& f,
                       const py::object& T, const py::object& amplitude, const std::string& mode,
                       const std::string& orientation, const ModuliAt& at) {
  const auto b = broadcast({{"frequency_Hz", f}, {"temperature_C", or_nan(T)}, {"strain_amplitude", amplitude}},
                           surface::kMaxCardGridPoints);
  const std::size_t n = b.columns[0].size();
  std::vector<double> storage(n), loss(n), mean(n), tan_delta(n);
  model::TestCondition c;
  c.mode = mode_or_native(m, mode);
  c.orientation = orientation;
  for (std::size_t i = 0; i < n; ++i) {
    // As fitcli eval's option checks: frequencies positive, amplitudes not negative.
    if (!(b.columns[0][i] > 0.0) || !std::isfinite(b.columns[0][i]) || !(b.columns[2][i] >= 0.0))
      throw core::UsageError("frequencies must be positive and amplitudes not negative, got " +
                             core::format_number(b.columns[0][i]) + " Hz, amplitude " + core::format_number(b.columns[2][i]));
    if (!std::isnan(b.columns[1][i])) require_in("temperature_C", b.columns[1][i], -273.15, 1000.0);
    require_in("strain_amplitude", b.columns[2][i], 0.0, 10.0);  // fitcli's --amplitude range
    c.frequency_Hz = b.columns[0][i];
    c.temperature_C = b.columns[1][i];
    c.strain_amplitude = b.columns[2][i];
    const auto r = at ? at(c) : m.moduli(p.data(), c);
    storage[i] = r.storage, loss[i] = r.loss, mean[i] = r.mean, tan_delta[i] = r.loss / r.storage;
  }
  py::dict out;
  out["storage_MPa"] = shaped(storage, b.shape);
  out["loss_MPa"] = shaped(loss, b.shape);
  out["tan_delta"] = shaped(tan_delta, b.shape);
  out["mean_modulus_MPa"] = shaped(mean, b.shape);
  return out;
}

namespace {

// Relaxation modulus M(t) or creep compliance J(t) over broadcast arrays of time and temperature.
template <typename Law>
py::array_t<double> time_array(const model::Model& m, const py::object& t, const py::object& T,
                               const std::string& mode, const std::string& orientation, Law law) {
  const auto b = broadcast({{"time_s", t}, {"temperature_C", or_nan(T)}}, surface::kMaxCardGridPoints);
  model::TestCondition c;
  c.mode = mode_or_native(m, mode);
  c.orientation = orientation;
  std::vector<double> out(b.columns[0].size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (!(b.columns[0][i] >= 0.0) || !std::isfinite(b.columns[0][i]))
      throw core::UsageError("times must be finite and not negative, got " + std::to_string(b.columns[0][i]));
    c.temperature_C = b.columns[1][i];
    out[i] = law(c, b.columns[0][i]);
  }
  return shaped(out, b.shape);
}

// M(t) or J(t) of the model with parameters p: the law is the Model member function.
template <double (model::Model::*Law)(const double*, const model::TestCondition&, double) const>
py::array_t<double> time_law(const model::Model& m, const Array& p, const Array& t, const OptionalArray& T,
                             const std::string& mode, const std::string& orientation) {
  const auto v = checked_values(m, p);
  return time_array(m, t.object, T.object, mode, orientation,
                    [&](const model::TestCondition& c, double t_s) { return (m.*Law)(v.data(), c, t_s); });
}

// ---- tables -------------------------------------------------------------------------------
template <typename Field>
py::array_t<double> column(const data::DynamicTestTable& t, Field field) {
  std::vector<double> v;
  v.reserve(t.rows.size());
  for (const auto& r : t.rows) v.push_back(field(r));
  return to_array(v);
}

template <typename Field>
std::vector<std::string> labels(const data::DynamicTestTable& t, Field field) {
  std::vector<std::string> v;
  for (const auto& r : t.rows) v.push_back(field(r));
  return v;
}

// A read-only property `name` of the table: field(row) of every row, as an array or a list.
template <typename Field>
void def_column(py::class_<data::DynamicTestTable>& table, const char* name, Field field) {
  table.def_property_readonly(name, [field](const data::DynamicTestTable& t) { return column(t, field); });
}

template <typename Field>
void def_labels(py::class_<data::DynamicTestTable>& table, const char* name, Field field) {
  table.def_property_readonly(name, [field](const data::DynamicTestTable& t) { return labels(t, field); });
}

data::ReadOptions read_options(const std::string& format, const std::string& mode,
                               bool skip_bad_rows, bool allow_unknown_columns) {
  if (format != "native" && format != "pyvisco" && format != "eplexor")
    throw core::UsageError("format must be native, pyvisco or eplexor, not '" + format + "'");
  data::ReadOptions o;
  o.format = format == "pyvisco" ? data::TableFormat::pyvisco : data::TableFormat::native;
  o.skip_bad_rows = skip_bad_rows;
  o.allow_unknown_columns = allow_unknown_columns;
  if (!mode.empty()) o.has_default_mode = true, o.default_mode = model::parse_test_mode(mode);
  return o;
}

// One file: EPLEXOR .xls when asked or recognised by its signature, CSV otherwise.
data::DynamicTestTable read_one(const std::string& path, const std::string& format,
                                const data::ReadOptions& o) {
  if (format == "eplexor" || data::is_ole_compound_file(core::read_file(path)))
    return data::read_eplexor(path, o).table;
  return data::read_dynamic_table(path, o);
}

data::DynamicTestTable read_table(const py::object& paths, const std::string& format,
                                  const std::string& mode, const Checked<bool>& skip_bad_rows,
                                  const Checked<bool>& allow_unknown_columns) {
  const auto o = read_options(format, mode, skip_bad_rows.get("skip_bad_rows"),
                              allow_unknown_columns.get("allow_unknown_columns"));
  const auto files = py::isinstance<py::str>(paths) ? std::vector<std::string>{paths.cast<std::string>()}
                                                    : paths.cast<std::vector<std::string>>();
  for (std::size_t i = 0; i < files.size(); ++i)  // as fitcli --data (fitcli/path_guard.cpp)
    for (std::size_t j = 0; j < i; ++j)
      if (core::same_file(files[i], files[j]))
        throw core::UsageError("paths: " + files[i] + " is given twice (also as " + files[j] +
                               "): its rows would count twice; give each file once");
  data::DynamicTestTable all;
  for (const auto& path : files) {
    auto one = read_one(path, format, o);
    all.rows.insert(all.rows.end(), one.rows.begin(), one.rows.end());
    all.source_files.insert(all.source_files.end(), one.source_files.begin(), one.source_files.end());
    all.source_sha256.insert(all.source_sha256.end(), one.source_sha256.begin(), one.source_sha256.end());
    all.warnings.insert(all.warnings.end(), one.warnings.begin(), one.warnings.end());
  }
  return all;
}

// A table from arrays: written as native CSV text and read back by the library's reader, so the
// arrays meet every check a file does (finite numbers, positive frequencies, magnitudes ≤ 1e100).
data::DynamicTestTable table_from_arrays(const Array& f, const Array& storage, const Array& loss,
                                         const OptionalArray& T, const OptionalArray& amplitude,
                                         const OptionalArray& mean_strain, const OptionalArray& weight,
                                         const std::string& mode) {
  Named given{{"frequency_Hz", f.object}, {"storage_MPa", storage.object}, {"loss_MPa", loss.object}};
  const Named optional{{"temperature_C", T.object}, {"strain_amplitude", amplitude.object},
                       {"mean_strain", mean_strain.object}, {"weight", weight.object}};
  for (const auto& [name, value] : optional)
    if (!value.is_none()) given.emplace_back(name, value);
  const auto columns = broadcast(given).columns;
  std::string text = "mode";
  for (const auto& named : given) text += std::string(",") + named.first;
  text += "\n";
  for (std::size_t i = 0; i < columns[0].size(); ++i) {
    text += mode;
    for (const auto& column : columns) text += "," + core::format_number(column[i]);
    text += "\n";
  }
  return data::parse_dynamic_table(text, "arrays", data::ReadOptions{});
}

void bind_table(py::module_& m) {
  using data::DynamicTestRow;
  using data::DynamicTestTable;
  py::class_<DynamicTestTable> table(m, "Table", "A dynamic-test table (formats.md §1); columns as NumPy arrays");
  table.def(py::init(&table_from_arrays), py::arg("frequency_Hz"), py::arg("storage_MPa"), py::arg("loss_MPa"),
            py::arg("temperature_C") = py::none(), py::arg("strain_amplitude") = py::none(),
            py::arg("mean_strain") = py::none(), py::arg("weight") = py::none(), py::arg("mode") = "shear",
            "A table from NumPy arrays (or numbers, broadcast): checked as the CSV reader checks a file "
            "(errors name 'arrays', line = index + 2)");
  table.def("__len__", [](const DynamicTestTable& t) { return t.rows.size(); });
  // Numeric columns as arrays (mean_modulus_MPa: NaN where a row has none), labels as lists.
  def_column(table, "frequency_Hz", [](const DynamicTestRow& r) { return r.condition.frequency_Hz; });
  def_column(table, "temperature_C", [](const DynamicTestRow& r) { return r.condition.temperature_C; });
  def_column(table, "strain_amplitude", [](const DynamicTestRow& r) { return r.condition.strain_amplitude; });
  def_column(table, "mean_strain", [](const DynamicTestRow& r) { return r.condition.mean_strain; });
  def_column(table, "storage_MPa", [](const DynamicTestRow& r) { return r.storage_MPa; });
  def_column(table, "loss_MPa", [](const DynamicTestRow& r) { return r.loss_MPa; });
  def_column(table, "mean_modulus_MPa",
             [](const DynamicTestRow& r) { return r.has_mean_modulus ? r.mean_modulus_MPa : kNaN; });
  def_column(table, "weight", [](const DynamicTestRow& r) { return r.weight; });
  def_column(table, "source_line", [](const DynamicTestRow& r) { return double(r.source_line); });
  def_labels(table, "mode", [](const DynamicTestRow& r) { return std::string(model::to_string(r.condition.mode)); });
  def_labels(table, "orientation", [](const DynamicTestRow& r) { return r.condition.orientation; });
  def_labels(table, "material", [](const DynamicTestRow& r) { return r.material; });
  def_labels(table, "specimen", [](const DynamicTestRow& r) { return r.specimen; });
  def_labels(table, "set", [](const DynamicTestRow& r) { return r.set; });
  table.def_readonly("source_files", &DynamicTestTable::source_files)
      .def_readonly("source_sha256", &DynamicTestTable::source_sha256)
      .def_readonly("warnings", &DynamicTestTable::warnings)
      .def("to_csv", &data::format_dynamic_table, "The native CSV text (exact doubles)")
      .def("save", [](const DynamicTestTable& t, const std::string& path) { data::write_dynamic_table(path, t); },
           py::arg("path"), "Writes the native CSV atomically");

  m.def("read_table", &read_table, py::arg("paths"), py::arg("format") = "native", py::arg("mode") = "",
        py::arg("skip_bad_rows") = false, py::arg("allow_unknown_columns") = false,
        "Reads one file or a list of files (native | pyvisco CSV, EPLEXOR .xls; .xls recognised by content)");
  m.def("parse_table",
        [](const std::string& text, const std::string& file_name, const std::string& format, const std::string& mode) {
          return data::parse_dynamic_table(text, file_name, read_options(format, mode, false, false));
        },
        py::arg("text"), py::arg("file_name") = "table", py::arg("format") = "native", py::arg("mode") = "", "A dynamic-test table from CSV text (native or pyvisco); file_name names it in errors");
  m.def("read_eplexor_shifts",
        [](const std::string& path) {
          const auto x = data::read_eplexor(path);
          py::dict d;
          d["has_shift_list"] = x.has_shift_list;
          d["reference_C"] = x.shifts.reference_C;
          d["wlf_C1"] = x.wlf_C1;
          d["wlf_C2_K"] = x.wlf_C2_K;
          std::vector<double> T, log_aT;
          for (const auto& f : x.shifts.factors) T.push_back(f.temperature_C), log_aT.push_back(f.log10_aT);
          d["temperature_C"] = to_array(T);
          d["log10_aT"] = to_array(log_aT);
          return d;
        },
        py::arg("path"), "The shift list of an EPLEXOR master export");
}

// ---- models --------------------------------------------------------------------------------
py::dict parameter_spec(const core::ParameterSpec& s) {
  py::dict d;
  d["name"] = s.name, d["unit"] = s.unit, d["lower"] = s.lower, d["upper"] = s.upper;
  d["log_transform"] = s.transform == core::Transform::log;
  d["group"] = s.group, d["default"] = s.default_value, d["linear"] = s.linear;
  return d;
}

void bind_model(py::module_& m) {
  using model::Model;
  py::class_<Model, std::shared_ptr<Model>>(m, "Model", "A constitutive law: pure functions of a parameter vector")
      .def_property_readonly("kind", &Model::kind)
      .def_property_readonly("size", &Model::size)
      .def_property_readonly("parameters", [](const Model& mo) {
        py::list out;
        for (const auto& s : mo.parameters()) out.append(parameter_spec(s));
        return out;
      })
      .def_property_readonly("parameter_names", [](const Model& mo) {
        std::vector<std::string> names;
        for (const auto& s : mo.parameters()) names.push_back(s.name);
        return names;
      })
      .def_property_readonly("options", [](const Model& mo) { return to_python(mo.options()); })
      .def_property_readonly("native_mode", [](const Model& mo) { return std::string(model::to_string(mo.native_mode())); })
      .def_property_readonly("amplitude_dependent", &Model::amplitude_dependent)
      .def("damage_drivers",
           [](const Model& mo, const Array& p, const std::string& mode, const std::string& orientation,
              const Checked<double>& strain_amplitude, const Checked<double>& frequency_Hz,
              const Checked<std::optional<double>>& temperature_C) {
             model::TestCondition c;
             c.mode = mode_or_native(mo, mode), c.orientation = orientation;
             c.strain_amplitude = strain_amplitude.get("strain_amplitude");
             c.frequency_Hz = frequency_Hz.get("frequency_Hz"), c.temperature_C = optional_temperature(temperature_C);
             return to_array(mo.damage_drivers(checked_values(mo, p).data(), c));
           },
           py::arg("p"), py::arg("mode") = "", py::arg("orientation") = "", py::arg("strain_amplitude") = 0.0,
           py::arg("frequency_Hz") = 1.0, py::arg("temperature_C") = py::none(),
           "The damage drivers a steady test reaches (empty for a model without damage)")
      .def("default_parameters", [](const Model& mo) { return to_array(mo.default_parameters()); })
      .def("temperature_law", [](const Model& mo, const Array& p) {
        return to_python(mo.temperature_law(checked_values(mo, p).data()));
      }, py::arg("p"))
      .def("moduli",
           [](const Model& mo, const Array& p, const Array& f, const OptionalArray& T, const Array& amplitude,
              const std::string& mode, const std::string& orientation) {
             return moduli_arrays(mo, checked_values(mo, p), f.object, T.object, amplitude.object, mode, orientation);
           },
           py::arg("p"), py::arg("frequency_Hz"), py::arg("temperature_C") = py::none(),
           py::arg("strain_amplitude") = 0.0, py::arg("mode") = "", py::arg("orientation") = "",
           "Storage, loss, tan δ and mean modulus over broadcast arrays (mode '' = the model's own)")
      .def("relaxation_modulus", &time_law<&Model::relaxation_modulus>, py::arg("p"), py::arg("time_s"),
           py::arg("temperature_C") = py::none(), py::arg("mode") = "", py::arg("orientation") = "")
      .def("creep_compliance", &time_law<&Model::creep_compliance>, py::arg("p"), py::arg("time_s"),
           py::arg("temperature_C") = py::none(), py::arg("mode") = "", py::arg("orientation") = "")
      .def("__repr__", [](const Model& mo) { return "<fitlib.Model " + mo.kind() + " " + mo.options().dump() + ">"; });

  m.def("model_kinds", &model::model_kinds, "The model kinds make_model builds");
  m.def("make_model",
        [](const std::string& kind, const py::object& options) {
          return std::const_pointer_cast<Model>(model::make_model(kind, to_json(options)));
        },
        py::arg("kind"), py::arg("options") = py::none(), "A model by name with its options (dict)");
}

}  // namespace

void bind_data_model(py::module_& m) {
  bind_table(m);
  bind_model(m);
}

}  // namespace fitlib::python

PYBIND11_MODULE(_fitlib, m) {
  m.doc() = "fitlib: viscoelastic material fitting, cards, surfaces and belt drives (docs/python.md)";
  m.attr("__version__") = FITLIB_VERSION;
  fitlib::python::bind_errors(m);
  fitlib::python::bind_data_model(m);
  fitlib::python::bind_fit_card(m);
  fitlib::python::bind_surface_point_scene(m);
  fitlib::python::bind_master_relaxation(m);
  fitlib::python::bind_segment_life(m);
  fitlib::python::bind_sweep(m);
  fitlib::python::bind_hyperelastic(m);
}
