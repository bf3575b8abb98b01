// Python bindings of fit (options, results, term selection) and card (load, save, JSON, eval,
// FE export). docs/python.md lists the names.
#include "bindings.hpp"
#include <cmath>

#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/card/data_window.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/card/fit_card.hpp"
#include "fitlib/card/from_fit.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/terms.hpp"

namespace fitlib::python {
namespace {

// Options objects built from keyword arguments, each set as the attribute of that name.
template <typename Options>
Options from_keywords(const py::kwargs& kwargs) {
  auto options = py::cast(Options{});
  for (const auto& item : kwargs) py::setattr(options, item.first, item.second);
  return options.template cast<Options>();
}

// fitcli's data window (fitcli/window_check.cpp) for Card.eval and Card.export: a temperature
// where the card's law describes no material is refused; a condition beyond the window is an
// InputError at fit.data_window.<key> unless allow_extrapolation, then one UserWarning.
class WindowGuard {
 public:
  WindowGuard(const card::Card& c, bool allow) : card_(c), window_(c), allow_(allow) {}
  void check(const model::TestCondition& at) {
    if (!std::isnan(at.temperature_C) && at.temperature_C != checked_T_) {
      card::require_material_at(card_, "card " + card_.name, at.temperature_C, "", "temperature_C");
      checked_T_ = at.temperature_C;
    }
    const auto excess = window_.outside(at);
    if (excess.empty()) return;
    const auto& x = excess.front();
    const std::string text = x.quantity + " " + core::format_number(x.value) + " is outside the card's data window [" +
                             core::format_number(x.low) + ", " + core::format_number(x.high) + "]";
    if (!allow_)
      throw core::InputError(text + "; pass allow_extrapolation=True to evaluate there anyway", "card " + card_.name,
                             0, 0, "fit.data_window." + x.key);
    if (first_.empty()) first_ = text;
  }
  void finish() const {
    if (!first_.empty()) warn("extrapolating: " + first_ + " (card " + card_.name + ")");
  }

 private:
  const card::Card& card_;
  card::DataWindow window_;
  bool allow_;
  double checked_T_ = std::nan("");
  std::string first_;
};

std::string method_name(fit::TermMethod m) { return m == fit::TermMethod::spectrum ? "spectrum" : "sweep"; }

void bind_fit_options(py::module_& m) {
  // Each field through def_field: a wrong type is a TypeError naming the field (issue 37).
  using fit::FitOptions;
  auto options = py::class_<FitOptions>(m, "FitOptions", "Options of fitlib.fit (fit/fit.hpp); keyword arguments set fields")
      .def(py::init(&from_keywords<FitOptions>));
  def_field<std::string>(options, "backend", [](const FitOptions& o) { return std::string(fit::to_string(o.backend)); },
                         [](FitOptions& o, const std::string& s) { o.backend = fit::parse_backend(s); });
  def_field<std::string>(options, "residual", [](const FitOptions& o) { return std::string(fit::to_string(o.residual)); },
                         [](FitOptions& o, const std::string& s) { o.residual = fit::parse_residual_kind(s); });
  def_field(options, "storage_weight", &FitOptions::storage_weight);
  def_field(options, "loss_weight", &FitOptions::loss_weight);
  def_field(options, "mean_weight", &FitOptions::mean_weight);
  def_field(options, "seed", &FitOptions::seed);
  def_field(options, "multistart", &FitOptions::multistart);
  def_field(options, "tolerance", &FitOptions::tolerance);
  def_field(options, "max_iterations", &FitOptions::max_iterations);
  def_field(options, "fixed", &FitOptions::fixed);
  def_field(options, "polish", &FitOptions::polish);
  def_field(options, "linear_start", &FitOptions::linear_start);
  def_field(options, "global_", &FitOptions::global);
  def_field(options, "schedule_path", &FitOptions::schedule_path);
  def_field(options, "tau_margin_decades", &FitOptions::tau_margin_decades);
  def_field(options, "modulus_ceiling", &FitOptions::modulus_ceiling);
  def_field(options, "relaxed_floor", &FitOptions::relaxed_floor);

  using fit::TermOptions;
  auto term_options = py::class_<TermOptions>(m, "TermOptions", "Options of fitlib.select_terms (fit/terms.hpp)")
      .def(py::init(&from_keywords<TermOptions>));
  def_field(term_options, "min_terms", &TermOptions::min_terms);
  def_field(term_options, "max_terms", &TermOptions::max_terms);
  def_field(term_options, "solver_cap", &TermOptions::solver_cap);
  def_field<std::string>(term_options, "rule", [](const TermOptions& o) { return std::string(fit::to_string(o.rule)); },
                         [](TermOptions& o, const std::string& s) { o.rule = fit::parse_term_rule(s); });
  def_field(term_options, "residual_ratio", &TermOptions::residual_ratio);
  def_field<std::string>(term_options, "method", [](const TermOptions& o) { return method_name(o.method); },
                         [](TermOptions& o, const std::string& s) { o.method = fit::parse_term_method(s); });
  def_field<double>(term_options, "smoothness", [](const TermOptions& o) { return o.spectrum.lambda; },
                    [](TermOptions& o, double v) { o.spectrum.lambda = v; });
  def_field<double>(term_options, "terms_per_decade", [](const TermOptions& o) { return o.spectrum.per_decade; },
                    [](TermOptions& o, double v) { o.spectrum.per_decade = v; });
  def_field<bool>(term_options, "spectrum_polish", [](const TermOptions& o) { return o.spectrum.polish; },
                  [](TermOptions& o, bool v) { o.spectrum.polish = v; });

  m.attr("SPECTRUM_RESIDUAL") = fit::to_string(fit::kSpectrumResidual);
  m.attr("SPECTRUM_STORAGE_WEIGHT") = fit::kSpectrumStorageWeight;
}

void bind_fit_result(py::module_& m) {
  using namespace fit;
  py::class_<ParameterResult>(m, "ParameterResult", "A fitted parameter: name, unit, value, fixed, std_error (None where not estimable), reason, ci95")
      .def_readonly("name", &ParameterResult::name)
      .def_readonly("unit", &ParameterResult::unit)
      .def_readonly("value", &ParameterResult::value)
      .def_readonly("fixed", &ParameterResult::fixed)
      .def_readonly("std_error", &ParameterResult::std_error)
      .def_readonly("reason", &ParameterResult::reason)
      .def_readonly("ci95_low", &ParameterResult::ci95_low)
      .def_readonly("ci95_high", &ParameterResult::ci95_high)
      .def("__repr__", [](const ParameterResult& p) {
        return "<" + p.name + " = " + std::to_string(p.value) + " " + p.unit + ">";
      });
  py::class_<FitMetrics>(m, "FitMetrics", "Figures of a fit's residuals (rms, max relative errors, ...)")
      .def_readonly("n_points", &FitMetrics::n_points)
      .def_readonly("n_residuals", &FitMetrics::n_residuals)
      .def_readonly("n_free", &FitMetrics::n_free)
      .def_readonly("cost", &FitMetrics::cost)
      .def_readonly("rms_log10_storage", &FitMetrics::rms_log10_storage)
      .def_readonly("rms_log10_loss", &FitMetrics::rms_log10_loss)
      .def_readonly("mean_rel_error", &FitMetrics::mean_rel_error)
      .def_readonly("max_rel_error", &FitMetrics::max_rel_error)
      .def_readonly("aic", &FitMetrics::aic)
      .def_readonly("bic", &FitMetrics::bic)
      .def_readonly("wall_time_s", &FitMetrics::wall_time_s)
      .def_readonly("converged", &FitMetrics::converged)
      .def_readonly("condition_number", &FitMetrics::condition_number)
      .def_readonly("rank", &FitMetrics::rank)
      .def_readonly("iterations", &FitMetrics::iterations)
      .def_readonly("n_active", &FitMetrics::n_active);
  py::class_<Identifiability>(m, "Identifiability", "Whether the data determine the parameters: condition number, rank, null space, correlations")
      .def_readonly("condition_number", &Identifiability::condition_number)
      .def_readonly("rank", &Identifiability::rank)
      .def_readonly("null_space", &Identifiability::null_space)
      .def_readonly("not_identifiable", &Identifiability::not_identifiable)
      .def_property_readonly("correlated", [](const Identifiability& i) {
        py::list out;
        for (const auto& p : i.correlated) out.append(py::make_tuple(p.a, p.b, p.correlation));
        return out;
      });
  py::class_<ErrorFigures>(m, "ErrorFigures", "Errors of one modulus of a fit (quality verdict, docs/fitting.md)")
      .def_readonly("group", &ErrorFigures::group)
      .def_readonly("modulus", &ErrorFigures::modulus)
      .def_readonly("count", &ErrorFigures::count)
      .def_readonly("mean_rel_error", &ErrorFigures::mean_rel_error)
      .def_readonly("max_rel_error", &ErrorFigures::max_rel_error)
      .def_readonly("max_at_frequency_Hz", &ErrorFigures::max_at_frequency_Hz);
  py::class_<QualityVerdict>(m, "QualityVerdict", "A fit's quality verdict: figures, warnings, acceptable")
      .def_readonly("figures", &QualityVerdict::figures)
      .def_readonly("warnings", &QualityVerdict::warnings)
      .def_property_readonly("acceptable", &QualityVerdict::acceptable);
  py::class_<FitResult>(m, "FitResult", "A fit: values, parameters, metrics, identifiability, quality, backend, messages")
      .def_property_readonly("model", [](const FitResult& r) { return std::const_pointer_cast<model::Model>(r.model); })
      .def_property_readonly("values", [](const FitResult& r) { return to_array(r.values); })
      .def_readonly("parameters", &FitResult::parameters)
      .def_readonly("metrics", &FitResult::metrics)
      .def_readonly("backend_used", &FitResult::backend_used)
      .def_readwrite("messages", &FitResult::messages)
      .def_readonly("identifiability", &FitResult::identifiability)
      .def_readonly("objective", &FitResult::objective)
      .def_property_readonly("admissible", [](const FitResult& r) {
        return r.admissible.applies ? to_python(card::admissible_to_json(r.admissible)) : py::none();
      })
      .def_readonly("quality", &FitResult::quality);

  m.def("fit",
        [](const std::shared_ptr<model::Model>& model, const data::DynamicTestTable& table,
           const FitOptions& options, const OptionalArray& start) {
          if (start.object.is_none()) return fit::fit(model, table, options);
          const auto p = to_vector(start.object, "start");
          return fit::fit(model, table, options, &p);
        },
        py::arg("model"), py::arg("table"), py::arg("options") = FitOptions{}, py::arg("start") = py::none(),
        "Fits `model` to `table` (start: the model's own from the data unless given)");
}

void bind_terms(py::module_& m) {
  using namespace fit;
  py::class_<TermRow>(m, "TermRow", "One row of a term selection: the fit with N terms and its criteria")
      .def_readonly("terms", &TermRow::terms)
      .def_readonly("wall_time_s", &TermRow::wall_time_s)
      .def_readonly("rms_log10_storage", &TermRow::rms_log10_storage)
      .def_readonly("rms_log10_loss", &TermRow::rms_log10_loss)
      .def_readonly("cost", &TermRow::cost)
      .def_readonly("aic", &TermRow::aic)
      .def_readonly("bic", &TermRow::bic)
      .def_readonly("n_free", &TermRow::n_free)
      .def_readonly("converged", &TermRow::converged)
      .def_readonly("failed", &TermRow::failed)
      .def_readonly("message", &TermRow::message);
  py::class_<TermSelection>(m, "TermSelection", "fitcli fit --terms auto: the rows, the number each rule picks, the chosen fit")
      .def_readonly("rows", &TermSelection::rows)
      .def_readonly("by_aic", &TermSelection::by_aic)
      .def_readonly("by_bic", &TermSelection::by_bic)
      .def_readonly("by_ratio", &TermSelection::by_ratio)
      .def_property_readonly("rule", [](const TermSelection& s) { return std::string(to_string(s.rule)); })
      .def_readonly("unconstrained", &TermSelection::unconstrained)
      .def_readonly("chosen", &TermSelection::chosen)
      .def_readonly("cap_cost_ratio", &TermSelection::cap_cost_ratio)
      .def_readonly("cap_storage_rms_ratio", &TermSelection::cap_storage_rms_ratio)
      .def_readonly("cap_loss_rms_ratio", &TermSelection::cap_loss_rms_ratio)
      .def_readonly("result", &TermSelection::result)
      .def_readonly("messages", &TermSelection::messages)
      .def_property_readonly("method", [](const TermSelection& s) { return method_name(s.method); })
      .def_readonly("spectrum_lambda", &TermSelection::spectrum_lambda)
      .def_property_readonly("spectrum_path", [](const TermSelection& s) {
        py::list out;
        for (const auto& r : s.spectrum_path) {
          py::dict d;
          d["lambda"] = r.lambda, d["gcv"] = r.gcv, d["effective_terms"] = r.effective_terms;
          d["terms"] = r.terms, d["residual_norm"] = r.residual_norm;
          out.append(d);
        }
        return out;
      })
      .def("table_text", &format_term_table, "The human term table the CLI prints");

  m.def("select_terms",
        [](const std::string& kind, const py::object& model_options, const data::DynamicTestTable& table,
           const FitOptions& options, const TermOptions& terms) {
          return select_terms(kind, to_json(model_options), table, options, terms);
        },
        py::arg("kind"), py::arg("model_options"), py::arg("table"), py::arg("options") = FitOptions{},
        py::arg("terms") = TermOptions{}, "--terms auto: the term count by the smooth spectrum or an N-sweep");
}

void bind_card(py::module_& m) {
  using card::Card;
  using card::ParameterEstimate;
  py::class_<ParameterEstimate>(m, "ParameterEstimate", "A card's parameter: name, unit, value, std_error, fixed")
      .def_readonly("value", &ParameterEstimate::value)
      .def_readonly("fixed", &ParameterEstimate::fixed)
      .def_readonly("std_error", &ParameterEstimate::std_error)
      .def_readonly("std_error_reason", &ParameterEstimate::std_error_reason)
      .def_readonly("ci95_low", &ParameterEstimate::ci95_low)
      .def_readonly("ci95_high", &ParameterEstimate::ci95_high);
  py::class_<Card>(m, "Card", "A material card (formats.md §3)")
      .def_readonly("name", &Card::name)
      .def_readonly("model_kind", &Card::model_kind)
      .def_property_readonly("model_options", [](const Card& c) { return to_python(c.model_options); })
      .def_readonly("parameters", &Card::parameters)
      .def_property_readonly("parameter_names", [](const Card& c) {
        const auto model = c.model();  // alive while its parameter list is read
        std::vector<std::string> names;
        for (const auto& s : model->parameters()) names.push_back(s.name);
        return names;
      })
      .def_property_readonly("fit", [](const Card& c) { return to_python(c.fit); })
      .def_property_readonly("provenance", [](const Card& c) { return to_python(c.provenance); })
      .def("model", [](const Card& c) { return std::const_pointer_cast<model::Model>(c.model()); })
      .def("values", [](const Card& c) { return to_array(c.values()); })
      .def("to_json", [](const Card& c) { return to_python(card::card_to_json(c)); })
      .def("to_json_text", [](const Card& c) { return card::card_to_json(c).dump(2) + "\n"; },
           "The bytes save() writes")
      .def("save", [](const Card& c, const std::string& path) { card::save_card(path, c); }, py::arg("path"))
      .def("eval",
           [](const Card& c, const Array& f, const OptionalArray& T, const Array& amplitude,
              const std::string& mode, const std::string& orientation, const Checked<double>& nu,
              const Checked<bool>& allow) {
             const double poisson_ratio = nu.get("poisson_ratio");
             const bool allow_extrapolation = allow.get("allow_extrapolation");
             require_in("poisson_ratio", poisson_ratio, 0.0, 0.4999999);
             const auto model = c.model();
             const auto values = c.values();
             WindowGuard window(c, allow_extrapolation);
             auto out = moduli_arrays(*model, values, f.object, T.object, amplitude.object, mode, orientation,
                                      [&](const model::TestCondition& at) {
                                        window.check(at);
                                        return card::moduli_in_mode(*model, values, at, poisson_ratio);
                                      });
             window.finish();
             return out;
           },
           py::arg("frequency_Hz"), py::arg("temperature_C") = py::none(), py::arg("strain_amplitude") = 0.0,
           py::arg("mode") = "", py::arg("orientation") = "", py::arg("poisson_ratio") = card::kDefaultPoissonRatio,
           py::arg("allow_extrapolation") = false,
           "fitcli eval over broadcast arrays: another mode converts as the export does (poisson_ratio, for a "
           "card without a bulk modulus); beyond the card's data window an InputError unless allow_extrapolation "
           "(then a UserWarning)")
      .def("export",
           [](const Card& c, const std::string& format, const Checked<double>& nu, const Checked<int>& id,
              const Checked<bool>& inadmissible, const Checked<double>& density,
              const Checked<std::optional<double>>& temperature_C, const Checked<bool>& allow) {
             card::ExportOptions o;
             const double poisson_ratio = nu.get("poisson_ratio"), density_t_per_mm3 = density.get("density_t_per_mm3");
             const int material_id = id.get("material_id");
             const bool allow_inadmissible = inadmissible.get("allow_inadmissible");
             const bool allow_extrapolation = allow.get("allow_extrapolation");
             const auto T = temperature_C.get("temperature_C");
             require_in("poisson_ratio", poisson_ratio, 0.0, 0.4999999);
             require_in("material_id", material_id, 1, 999999);  // fitcli export --material-id
             require_in("density_t_per_mm3", density_t_per_mm3, 0.0, 1e-6);
             o.poisson_ratio = poisson_ratio, o.material_id = material_id, o.allow_inadmissible = allow_inadmissible;
             o.density_t_per_mm3 = density_t_per_mm3;
             if (T) {
               o.temperature_C = *T;
               require_in("temperature_C", o.temperature_C, -273.15, 1000.0);
               WindowGuard window(c, allow_extrapolation);  // the temperature alone, as fitcli export
               model::TestCondition at;
               at.frequency_Hz = std::nan(""), at.temperature_C = o.temperature_C;
               window.check(at);
               window.finish();
             }
             return card::export_card(c, format, o);
           },
           py::arg("format"), py::arg("poisson_ratio") = 0.4995, py::arg("material_id") = 1,
           py::arg("allow_inadmissible") = false, py::arg("density_t_per_mm3") = 0.0, py::arg("temperature_C") = py::none(),
           py::arg("allow_extrapolation") = false,
           "FE keywords: abaqus | ansys | lsdyna (fitlib.export_formats()); temperature_C: the card at one temperature "
           "(fitcli export --temperature-c; beyond the data window refused unless allow_extrapolation)")
      .def("admissibility_problems", &card::admissibility_problems);

  m.def("load_card", &card::load_card, py::arg("path"), "Reads and validates a material card (formats.md §3); InputError names the file and key");
  m.def("card_from_json",
        [](const py::object& j, const std::string& source) { return card::card_from_json(to_json(j), source); },
        py::arg("document"), py::arg("source") = "card", "A card from its JSON document (a dict), validated as load_card; source names it in errors");
  m.def("card_from_fit",
        [](const fit::FitResult& r, const fit::FitOptions& o, const data::DynamicTestTable& t, const std::string& name,
           const std::string& command, const Checked<bool>& record_timing) {
          return card::card_from_fit(r, o, t, {name, command, record_timing.get("record_timing")});
        },
        py::arg("result"), py::arg("options"), py::arg("table"), py::arg("name"), py::arg("command") = "",
        py::arg("record_timing") = false, "The card of a fit: parameters with uncertainty, the fit's figures, data files and window");
  m.def("max_prony_terms", &card::max_prony_terms, py::arg("format"), "The most Prony terms the FE format takes (abaqus, ansys, lsdyna)");
  m.def("export_formats", &card::export_formats, "The formats Card.export writes");
}

// fitlib.fit_card's one call into the library (card/fit_card.hpp, as fitcli fit).
void bind_fit_table_card(py::module_& m) {
  m.def("fit_table_card",
        [](const data::DynamicTestTable& table, const std::string& model, const std::string& terms,
           const py::object& model_options, const fit::FitOptions& options, const fit::TermOptions& term_options,
           const std::string& name, const std::string& command, const Checked<bool>& record_timing) {
          card::FitCardOptions o;
          o.model = model, o.terms = terms, o.model_options = to_json(model_options);
          o.fit = options, o.term = term_options, o.max_terms = term_options.solver_cap;
          const fit::FitOptions defaults;  // an objective left at its defaults is --terms auto's to choose
          o.objective_given = options.residual != defaults.residual || options.storage_weight != defaults.storage_weight ||
                              options.loss_weight != defaults.loss_weight;
          o.provenance = {name, command, record_timing.get("record_timing")};
          auto r = card::fit_card(table, o);
          return py::make_tuple(r.card, r.result, r.selection ? py::cast(*r.selection) : py::none());
        },
        py::arg("table"), py::arg("model"), py::arg("terms"), py::arg("model_options"), py::arg("options"),
        py::arg("term_options"), py::arg("name"), py::arg("command") = "", py::arg("record_timing") = false,
        "(card, result, selection) of card::fit_card; fitlib.fit_card is the keyword front");
}

}  // namespace

void bind_fit_card(py::module_& m) {
  bind_fit_options(m);
  bind_fit_result(m);
  bind_terms(m);
  bind_card(m);
  bind_fit_table_card(m);
}

}  // namespace fitlib::python
