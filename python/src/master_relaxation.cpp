// The Python module: master curves (raw isotherms → shifts → WLF/Arrhenius/polynomial laws,
// pyvisco shift files) and relaxation data (E(t) tables, fits, M(t)/J(t) of a card). A thin layer
// over fit/master_curve.hpp, fit/shift_laws.hpp, fit/relaxation.hpp and data/*.hpp
// (docs/python.md).
#include <algorithm>
#include <cmath>

#include "bindings.hpp"
#include "fitlib/card/card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/shift_factors.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/relaxation.hpp"
#include "fitlib/fit/shift_laws.hpp"

namespace fitlib::python {
namespace {

// One column of a vector of rows as a NumPy array.
template <typename Row, typename Field>
py::array_t<double> column_of(const std::vector<Row>& rows, Field field) {
  std::vector<double> v;
  v.reserve(rows.size());
  for (const auto& r : rows) v.push_back(field(r));
  return to_array(v);
}

fit::VerticalShift vertical_shift(const std::string& name) {
  if (name == "none") return fit::VerticalShift::none;
  if (name == "entropic") return fit::VerticalShift::entropic;
  if (name == "fitted") return fit::VerticalShift::fitted;
  throw core::UsageError("vertical shift '" + name + "' (none, entropic or fitted)");
}

data::ShiftFactorTable shift_table(const Array& temperatures_C, const Array& log10_aT,
                                   const Checked<std::optional<double>>& reference) {
  const auto T = to_vector(temperatures_C.object, "temperature_C"), a = to_vector(log10_aT.object, "log10_aT");
  const double reference_C = optional_temperature(reference, "reference_C");
  if (T.size() != a.size()) throw core::UsageError("temperatures and log10 a_T differ in length");
  for (std::size_t i = 0; i < T.size(); ++i) {
    require_in("temperature_C", T[i], -273.15, 1000.0);
    require_in("log10_aT", a[i], -1e3, 1e3);
  }
  auto sorted = T;  // as the shift file's reader: two shifts at one temperature are refused
  std::sort(sorted.begin(), sorted.end());
  if (const auto twice = std::adjacent_find(sorted.begin(), sorted.end()); twice != sorted.end())
    throw core::UsageError("temperature_C " + core::format_number(*twice) + " is listed twice");
  data::ShiftFactorTable table;
  table.reference_C = reference_C;
  for (std::size_t i = 0; i < T.size(); ++i) table.factors.push_back({T[i], a[i]});
  return table;
}

void bind_shift_factors(py::module_& m) {
  using data::ShiftFactorTable;
  py::class_<ShiftFactorTable>(m, "ShiftFactorTable", "Shift factors T, log10 a_T (pyvisco's file, docs/data.md §3)")
      .def(py::init(&shift_table), py::arg("temperature_C"), py::arg("log10_aT"), py::arg("reference_C") = py::none())
      .def_readonly("reference_C", &ShiftFactorTable::reference_C)
      .def_readonly("source_file", &ShiftFactorTable::source_file)
      .def_property_readonly("temperature_C", [](const ShiftFactorTable& t) {
        return column_of(t.factors, [](const data::ShiftFactor& f) { return f.temperature_C; });
      })
      .def_property_readonly("log10_aT", [](const ShiftFactorTable& t) {
        return column_of(t.factors, [](const data::ShiftFactor& f) { return f.log10_aT; });
      })
      .def("__len__", [](const ShiftFactorTable& t) { return t.factors.size(); })
      .def("interpolate",
           [](const ShiftFactorTable& t, const Checked<double>& T, const Checked<double>& tolerance) {
             return data::interpolate_log10_aT(t, T.get("temperature_C"), tolerance.get("tolerance_C"));
           },
           py::arg("temperature_C"), py::arg("tolerance_C") = 0.5,
           "log10 a_T at T, linear between the nearest tabulated temperatures")
      .def("to_csv", &data::format_shift_factors, "pyvisco's text (T,log_aT / C,-)")
      .def("save", [](const ShiftFactorTable& t, const std::string& path) {
        core::write_file_atomically(path, data::format_shift_factors(t));
      }, py::arg("path"));
  m.def("read_shift_factors", &data::read_shift_factors, py::arg("path"), "Reads pyvisco's shift-factor file (T,log_aT; docs/data.md §3)");
  m.def("parse_shift_factors", &data::parse_shift_factors, py::arg("text"), py::arg("file_name") = "shifts", "Shift factors from pyvisco's text; file_name names it in errors");
}

py::dict wlf_dict(const fit::WlfFit& w) {
  py::dict d;
  d["C1"] = w.C1, d["C2_K"] = w.C2_K, d["rms_decades"] = w.rms_decades;
  return d;
}

py::dict arrhenius_dict(const fit::ArrheniusFit& a) {
  py::dict d;
  d["activation_energy_kJ_mol"] = a.activation_energy_kJ_mol, d["rms_decades"] = a.rms_decades;
  return d;
}

py::dict isotherm_dict(const fit::IsothermShift& s) {
  py::dict d;
  d["set"] = s.set, d["temperature_C"] = s.temperature_C, d["log10_aT"] = s.log10_aT;
  d["log10_bT"] = s.log10_bT, d["pair_rms_decades"] = s.pair_rms_decades;
  d["pair_overlap_points"] = s.pair_overlap_points, d["rows"] = s.rows;
  return d;
}

void bind_master_options(py::module_& m) {
  using fit::MasterCurveOptions;
  auto options = py::class_<MasterCurveOptions>(m, "MasterCurveOptions", "Options of build_master_curve (fit/master_curve.hpp)")
      .def(py::init([](const py::kwargs& fields) {
        MasterCurveOptions o;
        py::object self = py::cast(o);
        for (const auto& [key, value] : fields) self.attr(key) = value;
        return self.cast<MasterCurveOptions>();
      }));
  // Each field through def_field: a wrong type is a TypeError naming the field (issue 37).
  def_field(options, "reference_C", &MasterCurveOptions::reference_C);
  def_field(options, "loss_weight", &MasterCurveOptions::loss_weight);
  def_field(options, "max_pair_shift_decades", &MasterCurveOptions::max_pair_shift_decades);
  def_field(options, "monotone", &MasterCurveOptions::monotone);
  def_field(options, "extrapolation_points", &MasterCurveOptions::extrapolation_points);
  def_field(options, "taper_decades", &MasterCurveOptions::taper_decades);
  def_field(options, "same_temperature_C", &MasterCurveOptions::same_temperature_C);
  def_field<std::string>(options, "vertical",
                         [](const MasterCurveOptions& o) {
                           return std::string(o.vertical == fit::VerticalShift::none       ? "none"
                                              : o.vertical == fit::VerticalShift::entropic ? "entropic"
                                                                                           : "fitted");
                         },
                         [](MasterCurveOptions& o, const std::string& v) { o.vertical = vertical_shift(v); });
}

void bind_master_curve(py::module_& m) {
  using fit::MasterCurve;
  bind_master_options(m);
  py::class_<MasterCurve>(m, "MasterCurve", "Shifted isotherms (fitcli fit --master-curve)")
      .def_readonly("reference_C", &MasterCurve::reference_C)
      .def_readonly("master", &MasterCurve::master, "The shifted rows as a Table")
      .def_readonly("messages", &MasterCurve::messages)
      .def_property_readonly("isotherms", [](const MasterCurve& c) {
        py::list out;
        for (const auto& s : c.isotherms) out.append(isotherm_dict(s));
        return out;
      })
      .def_property_readonly("temperature_C", [](const MasterCurve& c) {
        return column_of(c.isotherms, [](const fit::IsothermShift& s) { return s.temperature_C; });
      })
      .def_property_readonly("log10_aT", [](const MasterCurve& c) {
        return column_of(c.isotherms, [](const fit::IsothermShift& s) { return s.log10_aT; });
      })
      .def_property_readonly("log10_bT", [](const MasterCurve& c) {
        return column_of(c.isotherms, [](const fit::IsothermShift& s) { return s.log10_bT; });
      })
      .def_property_readonly("wlf", [](const MasterCurve& c) { return wlf_dict(c.wlf); })
      .def_property_readonly("arrhenius", [](const MasterCurve& c) { return arrhenius_dict(c.arrhenius); })
      .def("shift_table", &fit::format_shift_table, "The text table fitcli prints")
      .def("shift_table_csv", &fit::shift_table_csv)
      .def("shift_factors", &fit::shift_factors_of, "As a ShiftFactorTable (fitcli --shifts-out)");
  m.def("build_master_curve", &fit::build_master_curve, py::arg("table"),
        py::arg("options") = fit::MasterCurveOptions{}, "Free per-isotherm shifts of raw isotherms");
  m.def("build_relaxation_master_curve", &fit::build_relaxation_master_curve, py::arg("table"),
        py::arg("options") = fit::MasterCurveOptions{},
        "Free per-isotherm shifts of raw relaxation isotherms (fitcli fit --master-curve on time data); "
        "its master is empty: shift_relaxation_table(table, curve.shift_factors(), reference_C)");
  m.def("master_curve_from_shift_factors",
        [](const data::DynamicTestTable& t, const data::ShiftFactorTable& shifts, const Checked<double>& reference_C) {
          return fit::master_curve_from_shift_factors(t, shifts, reference_C.get("reference_C"));
        },
        py::arg("table"),
        py::arg("shifts"), py::arg("reference_C"), "Raw isotherms shifted by given factors (fitcli --shifts)");
  m.def("apply_shifts",
        [](MasterCurve curve, const data::DynamicTestTable& raw, const Array& log10_aT) {
          fit::apply_shifts(curve, raw, to_vector(log10_aT.object, "log10_aT"));
          return curve;
        },
        py::arg("curve"), py::arg("table"), py::arg("log10_aT"), "A copy of the curve with new shifts");
}

// The shifts a law is fitted to: as many temperatures as log10 a_T, at least `needed` of them,
// every number finite and in range (fit_wlf returned a dict of NaN for empty or mismatched input).
std::pair<std::vector<double>, std::vector<double>> shift_points(const Array& T, const Array& a, double ref,
                                                                 int needed, const char* law) {
  const auto table = shift_table(T, a, {py::float_(ref)});
  require_in("reference_C", ref, -273.15, 1000.0);
  if (table.factors.size() < static_cast<std::size_t>(needed))
    throw core::UsageError(std::string(law) + " shift law: needs at least " + std::to_string(needed) +
                           " shifts, got " + std::to_string(table.factors.size()));
  std::pair<std::vector<double>, std::vector<double>> out;
  for (const auto& f : table.factors) out.first.push_back(f.temperature_C), out.second.push_back(f.log10_aT);
  return out;
}

void bind_shift_laws(py::module_& m) {
  m.def("fit_wlf",
        [](const Array& T, const Array& a, const Checked<double>& reference_C) {
          const double ref = reference_C.get("reference_C");
          const auto [t, s] = shift_points(T, a, ref, 3, "WLF");
          return wlf_dict(fit::fit_wlf(t, s, ref));
        },
        py::arg("temperature_C"), py::arg("log10_aT"), py::arg("reference_C"), "WLF law fitted to shifts: dict C1, C2_K, rms_decades (at least 3 shifts, as many T as log10 a_T)");
  m.def("fit_arrhenius",
        [](const Array& T, const Array& a, const Checked<double>& reference_C) {
          const double ref = reference_C.get("reference_C");
          const auto [t, s] = shift_points(T, a, ref, 2, "Arrhenius");
          return arrhenius_dict(fit::fit_arrhenius(t, s, ref));
        },
        py::arg("temperature_C"), py::arg("log10_aT"), py::arg("reference_C"), "Arrhenius law fitted to shifts: dict activation_energy_kJ_mol, rms_decades (at least 2 shifts)");
  m.def("fit_polynomial_shift",
        [](const Array& T, const Array& a, const Checked<double>& reference_C, const Checked<int>& n) {
          const double ref = reference_C.get("reference_C");
          const int degree = n.get("degree");
          require_in("degree", degree, 1, 6);  // fitcli --polynomial-degree
          const auto [t, s] = shift_points(T, a, ref, degree, "polynomial");
          const auto p = fit::fit_polynomial_shift(t, s, ref, degree);
          py::dict d;
          d["coefficients"] = to_array(p.coefficients), d["rms_decades"] = p.rms_decades;
          return d;
        },
        py::arg("temperature_C"), py::arg("log10_aT"), py::arg("reference_C"), py::arg("degree") = 3, "pyvisco's polynomial law: dict coefficients (C_1..C_degree), rms_decades (degree 1..6)");
  m.def("given_log10_aT",
        [](const data::ShiftFactorTable& shifts, const Checked<double>& T, const Checked<double>& reference_C) {
          return fit::given_log10_aT(shifts, T.get("temperature_C"), reference_C.get("reference_C"));
        },
        py::arg("shifts"), py::arg("temperature_C"), py::arg("reference_C"), "log10 a_T of given shift factors at T, relative to reference_C");
  m.def("fit_master_curve",
        [](const std::shared_ptr<model::Model>& model, const data::DynamicTestTable& raw,
           const fit::MasterCurveOptions& curve_options, const fit::FitOptions& fit_options,
           const Checked<bool>& refine) {
          auto r = fit::fit_master_curve(model, raw, curve_options, fit_options, refine.get("refine_shifts"));
          py::dict d;
          d["curve"] = r.curve, d["master"] = r.master;
          d["joint"] = r.joint ? py::cast(*r.joint) : py::none();
          d["pairwise_log10_aT"] = to_array(r.pairwise_log10_aT);
          return d;
        },
        py::arg("model"), py::arg("table"), py::arg("curve_options") = fit::MasterCurveOptions{},
        py::arg("fit_options") = fit::FitOptions{}, py::arg("refine_shifts") = false,
        "Master curve, the model fitted to it, and optionally shifts and model refined together");
  m.def("with_wlf_from_shifts", &fit::with_wlf_from_shifts, py::arg("result"), py::arg("curve"), "The fit's model with WLF fitted to the master curve's shifts, constants held");
  m.def("with_law_from_shifts",
        [](const fit::FitResult& r, const Array& T, const Array& a, const Checked<double>& reference_C,
           const std::string& law, const Checked<int>& degree) {
          return fit::with_law_from_shifts(r, to_vector(T.object, "temperature_C"), to_vector(a.object, "log10_aT"),
                                           reference_C.get("reference_C"), model::parse_shift_law(law),
                                           degree.get("polynomial_degree"));
        },
        py::arg("result"), py::arg("temperature_C"), py::arg("log10_aT"), py::arg("reference_C"),
        py::arg("law") = "wlf", py::arg("polynomial_degree") = 3,
        "The fit's model with the law (wlf | polynomial) fitted to the shifts, constants held");
}

void bind_relaxation(py::module_& m) {
  using data::RelaxationRow;
  using data::RelaxationTable;
  py::class_<RelaxationTable>(m, "RelaxationTable", "Relaxation tests t, M(t) (docs/data.md §4)")
      .def("__len__", [](const RelaxationTable& t) { return t.rows.size(); })
      .def_property_readonly("time_s", [](const RelaxationTable& t) {
        return column_of(t.rows, [](const RelaxationRow& r) { return r.time_s; });
      })
      .def_property_readonly("modulus_MPa", [](const RelaxationTable& t) {
        return column_of(t.rows, [](const RelaxationRow& r) { return r.modulus_MPa; });
      })
      .def_property_readonly("temperature_C", [](const RelaxationTable& t) {
        return column_of(t.rows, [](const RelaxationRow& r) { return r.temperature_C; });
      })
      .def_property_readonly("weight", [](const RelaxationTable& t) {
        return column_of(t.rows, [](const RelaxationRow& r) { return r.weight; });
      })
      .def_property_readonly("mode", [](const RelaxationTable& t) {
        std::vector<std::string> v;
        for (const auto& r : t.rows) v.push_back(model::to_string(r.mode));
        return v;
      })
      .def_property_readonly("set", [](const RelaxationTable& t) {
        std::vector<std::string> v;
        for (const auto& r : t.rows) v.push_back(r.set);
        return v;
      })
      .def_readonly("source_files", &RelaxationTable::source_files)
      .def_readonly("source_sha256", &RelaxationTable::source_sha256);
  m.def("read_relaxation_table", &data::read_relaxation_table, py::arg("path"), "Reads pyvisco's relaxation table (t, E_relax; docs/data.md §4)");
  m.def("parse_relaxation_table", &data::parse_relaxation_table, py::arg("text"), py::arg("file_name") = "relaxation", "A relaxation table from pyvisco's text; file_name names it in errors");
  m.def("shift_relaxation_table",
        [](const RelaxationTable& t, const data::ShiftFactorTable& shifts, const Checked<double>& reference_C) {
          return fit::shift_relaxation_table(t, shifts, reference_C.get("reference_C"));
        },
        py::arg("table"), py::arg("shifts"),
        py::arg("reference_C"), "Rows at reduced time t / a_T (fitcli fit --shifts on relaxation data)");
  m.def("fit_relaxation",
        [](const std::shared_ptr<model::Model>& model, const RelaxationTable& t, const fit::FitOptions& o) {
          return fit::fit_relaxation(model, t, o);
        },
        py::arg("model"), py::arg("table"), py::arg("options") = fit::FitOptions{}, "A model fitted to relaxation data M(t) (fitcli fit on t, E_relax files)");
  m.def("select_relaxation_terms",
        [](const std::string& kind, const py::object& options, const RelaxationTable& t, const fit::FitOptions& o,
           const fit::TermOptions& terms) { return fit::select_relaxation_terms(kind, to_json(options), t, o, terms); },
        py::arg("kind"), py::arg("model_options"), py::arg("table"), py::arg("options") = fit::FitOptions{},
        py::arg("terms") = fit::TermOptions{}, "fitcli fit --terms auto on relaxation data");
  m.def("measure_relaxation",
        [](const std::shared_ptr<model::Model>& model, const Array& p, const RelaxationTable& t) {
          const auto r = fit::measure_relaxation(*model, to_vector(p.object, "p"), t);
          py::dict d;
          d["rms_log10"] = r.rms_log10, d["rms_relative"] = r.rms_relative;
          d["max_relative"] = r.max_relative, d["mean_relative"] = r.mean_relative;
          return d;
        },
        py::arg("model"), py::arg("p"), py::arg("table"), "Errors of M(t) of a model against relaxation data: rms_log10, rms/max/mean relative");
}

}  // namespace

void bind_master_relaxation(py::module_& m) {
  bind_shift_factors(m);
  bind_master_curve(m);
  bind_shift_laws(m);
  bind_relaxation(m);
}

}  // namespace fitlib::python
