// fitcli fit: dynamic-test tables → fitted model → material card (docs/formats.md §3, §6).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "fitlib/card/from_fit.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/eplexor.hpp"
#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/shift_factors.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/relaxation.hpp"
#include "fitlib/fit/shift_laws.hpp"
#include "fitlib/fit/terms.hpp"
#include "inputs.hpp"
#include "output.hpp"

namespace fitcli {
namespace {

// ---- --master-curve (fit/master_curve.hpp): raw isotherms → free per-isotherm shifts → the
// model is fitted to the master table at --reference-c; the card gets the WLF law fitted to the
// shifts (C1, C2 fixed). Shift table on stdout (stderr with --json), CSV with --shifts-out.
struct MasterCurveArgs {
  bool enabled = false;
  std::string shifts_out;
  std::string shifts_in;  // --shifts: given shift factors (pyvisco file) instead of fitted ones
  std::optional<fitlib::fit::MasterCurve> curve;
};

fitlib::data::DynamicTestTable master_curve_table(MasterCurveArgs& m, double reference_C, bool json,
                                                  const std::string& temperature_law,
                                                  fitlib::data::DynamicTestTable raw) {
  if (!m.enabled && m.shifts_in.empty()) return raw;
  if (temperature_law != "none" && temperature_law != "wlf" && temperature_law != "polynomial")
    throw fitlib::core::UsageError("--master-curve/--shifts fit the card's temperature law to the shifts: "
                                   "--temperature-law wlf (default) or polynomial");
  if (!m.shifts_in.empty()) {
    m.curve = fitlib::fit::master_curve_from_shift_factors(raw, fitlib::data::read_shift_factors(m.shifts_in),
                                                           reference_C);
  } else {
    fitlib::fit::MasterCurveOptions options;
    options.reference_C = reference_C;
    m.curve = fitlib::fit::build_master_curve(raw, options);
  }
  (json ? std::cerr : std::cout) << fitlib::fit::format_shift_table(*m.curve) << "\n";
  return m.curve->master;
}
// ---- end --master-curve

struct FitArgs {
  std::vector<std::string> data;
  std::string model, terms = "4", backend = "auto", format = "native", mode, out, name;
  std::string temperature_law = "none", residual = "log10", term_rule = "bic", term_method = "spectrum";
  double smoothness = -1.0, terms_per_decade = 2.0;  // --terms auto, method spectrum
  bool objective_given = false;  // --residual, --storage-weight or --loss-weight on the command line
  int polynomial_degree = 3;
  double reference_C = 23.0;
  bool bulk_modulus = false, skip_bad_rows = false, json = false, record_timing = false;
  int max_terms = 0, term_search_max = 0;
  fitlib::fit::FitOptions fit;
  std::string command_line;
  MasterCurveArgs master;  // --master-curve
};

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

// --terms N (not auto), checked against --max-terms.
int fixed_terms(const FitArgs& a) {
  int n = 0;
  try {
    n = std::stoi(a.terms);
  } catch (const std::exception&) {
    throw fitlib::core::UsageError("--terms takes a number or 'auto', got '" + a.terms + "'");
  }
  if (a.max_terms > 0 && n > a.max_terms)
    throw fitlib::core::UsageError("--terms " + a.terms + " exceeds --max-terms " + std::to_string(a.max_terms));
  return n;
}

fitlib::fit::TermOptions term_options(const FitArgs& a) {
  fitlib::fit::TermOptions t;
  t.max_terms = a.term_search_max;
  t.solver_cap = a.max_terms;
  t.rule = fitlib::fit::parse_term_rule(a.term_rule);
  t.method = fitlib::fit::parse_term_method(a.term_method);
  t.spectrum.lambda = a.smoothness;
  t.spectrum.per_decade = a.terms_per_decade;
  t.spectrum.polish = a.fit.polish;
  return t;
}

// The fit and, with --terms auto, the term table (text and JSON).
struct Selection {
  fitlib::fit::FitResult result;
  std::string table;
  nlohmann::json json;
  void take(fitlib::fit::TermSelection selection) {
    table = fitlib::fit::format_term_table(selection);
    json = {{"by_aic", selection.by_aic}, {"by_bic", selection.by_bic}, {"by_ratio", selection.by_ratio},
            {"rule", fitlib::fit::to_string(selection.rule)}, {"chosen", selection.chosen},
            {"unconstrained", selection.unconstrained}, {"cap_cost_ratio", selection.cap_cost_ratio},
            {"cap_storage_rms_ratio", selection.cap_storage_rms_ratio},
            {"cap_loss_rms_ratio", selection.cap_loss_rms_ratio},
            {"method", selection.method == fitlib::fit::TermMethod::spectrum ? "spectrum" : "sweep"}};
    if (selection.method == fitlib::fit::TermMethod::spectrum) {
      json["lambda"] = selection.spectrum_lambda;
      json["lambda_path"] = nlohmann::json::array();
      for (const auto& r : selection.spectrum_path)
        json["lambda_path"].push_back({{"lambda", r.lambda}, {"gcv", r.gcv}, {"effective_terms", r.effective_terms},
                                       {"terms", r.terms}, {"residual_norm", r.residual_norm}});
    }
    json["rows"] = nlohmann::json::array();
    for (const auto& row : selection.rows)
      json["rows"].push_back({{"terms", row.terms}, {"wall_time_s", row.wall_time_s},
                              {"rms_log10_storage", row.rms_log10_storage},
                              {"rms_log10_loss", row.rms_log10_loss}, {"cost", row.cost},
                              {"aic", row.aic}, {"bic", row.bic}, {"failed", row.failed}});
    result = std::move(selection.result);
    result.messages.insert(result.messages.end(), selection.messages.begin(), selection.messages.end());
  }
};

// --master-curve, --shifts: the card's law (WLF or polynomial) fitted to the isotherm shifts.
fitlib::fit::FitResult with_shift_law(const FitArgs& a, fitlib::fit::FitResult result,
                                      const std::optional<fitlib::fit::MasterCurve>& curve) {
  if (!curve) return result;
  std::vector<double> temperatures, log10_aT;
  for (const auto& iso : curve->isotherms) {
    temperatures.push_back(iso.temperature_C);
    log10_aT.push_back(iso.log10_aT);
  }
  return fitlib::fit::with_law_from_shifts(result, temperatures, log10_aT, curve->reference_C,
                                           a.temperature_law == "polynomial" ? fitlib::model::ShiftLaw::polynomial
                                                                             : fitlib::model::ShiftLaw::wlf,
                                           a.polynomial_degree);
}

// Writes the card (--out) and prints the summary or, with --json, the card and run figures.
void finish(const FitArgs& a, const fitlib::fit::FitResult& result, const fitlib::data::DynamicTestTable& table,
            const Selection& sel) {
  using namespace fitlib;
  const auto card = card::card_from_fit(
      result, a.fit, table, {a.name.empty() ? a.model + "-fit" : a.name, a.command_line, a.record_timing});
  if (!a.out.empty()) card::save_card(a.out, card);
  if (!a.master.shifts_out.empty() && a.master.curve)
    core::write_file_atomically(a.master.shifts_out, data::format_shift_factors(fit::shift_factors_of(*a.master.curve)));
  for (const auto& w : result.quality.warnings) std::cerr << "fitcli: warning: " << w << "\n";

  if (a.json) {
    auto j = card::card_to_json(card);
    if (a.record_timing) j["fit"]["wall_time_s"] = result.metrics.wall_time_s;
    if (!sel.json.is_null()) j["term_selection"] = sel.json;
    std::cout << j.dump(2) << "\n";
    return;
  }
  const auto& m = result.metrics;
  if (!sel.table.empty()) std::cout << sel.table << "\n";
  std::cout << "model " << card.model_kind << " (" << card.model_options.dump() << "), backend "
            << result.backend_used << "\n";
  std::cout << "points " << m.n_points << ", free parameters " << m.n_free << ", converged "
            << (m.converged ? "yes" : "no") << ", wall time " << m.wall_time_s * 1e3 << " ms\n";
  std::cout << "rms log10 error: storage " << m.rms_log10_storage << ", loss " << m.rms_log10_loss
            << "; relative error mean " << m.mean_rel_error << ", max " << m.max_rel_error << "\n";
  for (const auto& f : result.quality.figures)
    std::cout << "  " << f.modulus << " (" << f.group << "): mean relative error " << 100.0 * f.mean_rel_error
              << " %, max " << 100.0 * f.max_rel_error << " % at " << f.max_at_frequency_Hz << " Hz\n";
  std::cout << "verdict: "
            << (result.quality.acceptable() ? "within the thresholds (docs/fitting.md)"
                                            : std::to_string(result.quality.warnings.size()) + " warning(s) on stderr")
            << "\n";
  for (const auto& p : result.parameters) {
    std::cout << "  " << p.name << " = " << exact(p.value) << " " << p.unit;
    if (p.std_error)
      std::cout << "  ± " << *p.std_error << "  [95 %: " << *p.ci95_low << ", " << *p.ci95_high << "]";
    else if (!p.reason.empty())
      std::cout << "  (" << p.reason << ")";
    std::cout << "\n";
  }
  for (const auto& msg : result.messages) std::cout << "note: " << msg << "\n";
  if (!a.out.empty()) std::cout << "card written to " << a.out << "\n";
}

bool relaxation_data(const FitArgs& a) { return is_relaxation_data(a.data, a.format); }

void run_fit_relaxation(FitArgs a);

void run_fit(FitArgs a) {
  using namespace fitlib;
  // Every output is checked before the work and written after it: no partial results.
  if (!a.out.empty()) core::check_output_path(a.out);
  if (!a.master.shifts_out.empty()) core::check_output_path(a.master.shifts_out);
  if (relaxation_data(a)) return run_fit_relaxation(a);
  data::ReadOptions read;
  read.format = a.format == "pyvisco" ? data::TableFormat::pyvisco : data::TableFormat::native;
  read.skip_bad_rows = a.skip_bad_rows;
  if (!a.mode.empty()) {
    read.has_default_mode = true;
    read.default_mode = model::parse_test_mode(a.mode);
  }
  const auto table = master_curve_table(a.master, a.reference_C, a.json, a.temperature_law, read_tables(a.data, a.format, read));
  for (const auto& w : table.warnings) std::cerr << "fitcli: warning: " << w << "\n";
  if (table.rows.empty()) throw core::InputError("no usable rows", join(a.data));

  const bool shifted = a.master.curve.has_value();
  nlohmann::json options = {{"temperature_law", shifted ? "none" : a.temperature_law}, {"reference_C", a.reference_C}};
  if (a.temperature_law == "polynomial" && !shifted) options["polynomial_degree"] = a.polynomial_degree;
  // The model describes the mode of the data unless the data mix modes.
  const auto mode = table.rows.front().condition.mode;
  options["mode"] = model::to_string(mode);
  if (a.bulk_modulus) options["bulk_modulus"] = true;
  a.fit.backend = fit::parse_backend(a.backend);
  a.fit.record_timing = a.record_timing;
  a.fit.residual = fit::parse_residual_kind(a.residual);

  Selection sel;
  const bool has_terms = model::make_model(a.model, options)->options().contains("terms");
  if (has_terms && a.terms == "auto") {
    const auto terms = term_options(a);
    if (terms.method == fit::TermMethod::spectrum && !a.objective_given) {
      a.fit.residual = fit::kSpectrumResidual;  // the default objective of --terms auto
      a.fit.storage_weight = fit::kSpectrumStorageWeight;
    }
    sel.take(fit::select_terms(a.model, options, table, a.fit, terms));
  } else {
    if (has_terms) options["terms"] = fixed_terms(a);
    sel.result = fit::fit(model::make_model(a.model, options), table, a.fit);
  }
  finish(a, with_shift_law(a, std::move(sel.result), a.master.curve), table, sel);
}

// Relaxation data (pyvisco t, E_relax): master curve, or raw isotherms with --shifts.
void run_fit_relaxation(FitArgs a) {
  using namespace fitlib;
  if (a.master.enabled) throw core::UsageError("--master-curve needs frequency data; give relaxation isotherms --shifts");
  data::RelaxationTable table = read_relaxation_tables(a.data);
  std::optional<fit::MasterCurve> shifts;  // only the isotherm list is used, for the card's law
  if (!a.master.shifts_in.empty()) {
    const auto given = data::read_shift_factors(a.master.shifts_in);
    table = fit::shift_relaxation_table(table, given, a.reference_C);
    shifts.emplace();
    shifts->reference_C = a.reference_C;
    for (const auto& f : given.factors)
      shifts->isotherms.push_back({"", f.temperature_C, fit::given_log10_aT(given, f.temperature_C, a.reference_C)});
  }
  nlohmann::json options = {{"temperature_law", shifts ? "none" : a.temperature_law},
                            {"reference_C", a.reference_C},
                            {"mode", model::to_string(table.rows.front().mode)}};
  if (!model::make_model(a.model, options)->options().contains("terms"))
    throw core::UsageError("relaxation data: --model must be a series model (prony)");
  Selection sel;
  if (a.terms == "auto") {
    sel.take(fit::select_relaxation_terms(a.model, options, table, a.fit, term_options(a)));
  } else {
    options["terms"] = fixed_terms(a);
    sel.result = fit::fit_relaxation(model::make_model(a.model, options), table, a.fit);
  }
  data::DynamicTestTable provenance;  // a card records its data files and their sha256
  provenance.source_files = table.source_files;
  provenance.source_sha256 = table.source_sha256;
  finish(a, with_shift_law(a, std::move(sel.result), shifts), provenance, sel);
}

}  // namespace

void register_fit(CLI::App& app) {
  auto a = std::make_shared<FitArgs>();
  auto* cmd = app.add_subcommand("fit", "Fit a model to dynamic-test tables and write a material card");
  cmd->add_option("--data", a->data, "Dynamic-test CSV file(s)")->required();
  cmd->add_option("--model", a->model, "prony | zener3 | retardation | fractional-zener | fritzson | fritzson-iso")
      ->required();
  cmd->add_option("--terms", a->terms, "Number of terms, or 'auto' (AIC, BIC and pyvisco's rule)")
      ->capture_default_str();
  cmd->add_option("--max-terms", a->max_terms, "Solver cap on terms (e.g. 13 Abaqus, 6 LS-DYNA); reports its cost");
  cmd->add_option("--term-search-max", a->term_search_max, "Largest N tried by --terms auto (0: from the data)");
  cmd->add_option("--term-rule", a->term_rule, "Rule that picks N for --terms auto: bic | aic | ratio")
      ->capture_default_str();
  cmd->add_option("--term-method", a->term_method,
                  "--terms auto: spectrum (smooth spectrum, GCV; Prony without a temperature law) | sweep")
      ->capture_default_str()->check(CLI::IsMember({"spectrum", "sweep"}));
  cmd->add_option("--smoothness", a->smoothness,
                  "Spectrum: second-difference penalty weight lambda (default: chosen by GCV)");
  cmd->add_option("--terms-per-decade", a->terms_per_decade, "Spectrum: time constants per decade")
      ->capture_default_str()->check(CLI::Range(0.25, 20.0));
  cmd->add_option("--backend", a->backend, "auto | nnls | ceres | nlopt | staged")->capture_default_str();
  cmd->add_option("--format", a->format,
                  "native | pyvisco (t, E_relax files are relaxation data) | eplexor (.xls, also recognised by content)")
      ->capture_default_str()->check(CLI::IsMember({"native", "pyvisco", "eplexor"}));
  cmd->add_option("--mode", a->mode, "Test mode for files without a mode column (shear | uniaxial | bulk)");
  cmd->add_option("--temperature-law", a->temperature_law, "none | wlf | arrhenius | polynomial")->capture_default_str();
  cmd->add_option("--polynomial-degree", a->polynomial_degree, "Degree of the polynomial shift law (1..6)")
      ->capture_default_str();
  cmd->add_option("--reference-c", a->reference_C, "Reference temperature, degC")->capture_default_str();
  cmd->add_flag("--bulk-modulus", a->bulk_modulus, "Add a constant bulk modulus K (mode conversion)");
  cmd->add_option("--residual", a->residual, "log10 | relative | complex (errors relative to |E*|)")
      ->capture_default_str()->check(CLI::IsMember({"log10", "relative", "complex"}));
  cmd->add_option("--storage-weight", a->fit.storage_weight,
                  "Weight of storage-modulus residuals (--terms auto default: 80, with --residual relative)")
      ->capture_default_str();
  cmd->add_option("--loss-weight", a->fit.loss_weight, "Weight of loss-modulus residuals")->capture_default_str();
  cmd->add_option("--mean-weight", a->fit.mean_weight, "Weight of mean-modulus residuals")->capture_default_str();
  cmd->add_option("--fixed", a->fit.fixed, "Parameters held at their start value")->delimiter(',');
  cmd->add_option("--multistart", a->fit.multistart, "Global starts (nlopt)")->capture_default_str();
  cmd->add_option("--tolerance", a->fit.tolerance, "Relative function tolerance")->capture_default_str();
  cmd->add_option("--max-iterations", a->fit.max_iterations, "Iteration limit per solve")->capture_default_str();
  cmd->add_option("--seed", a->fit.seed, "Random seed (multistart)")->capture_default_str();
  cmd->add_option("--schedule", a->fit.schedule_path, "Staged backend: schedule of parameter groups (JSON or TOML)");
  cmd->add_flag("--global", a->fit.global, "auto backend: run the NLopt multistart before Ceres");
  cmd->add_flag("!--no-polish", a->fit.polish, "nnls backend: keep the pure linear solve (no log-space polish)");
  cmd->add_flag("--skip-bad-rows", a->skip_bad_rows, "Skip bad rows with a listed warning instead of failing");
  cmd->add_option("--out", a->out, "Card file to write (atomically)");
  cmd->add_option("--name", a->name, "Material name in the card");
  cmd->add_flag("--record-timing", a->record_timing, "Store the wall time in the card (breaks byte-identity)");
  a->fit.progress = true;  // shown only when stderr is a terminal
  cmd->add_flag("!--no-progress", a->fit.progress, "Hide the progress of multistart runs on stderr");
  cmd->add_flag("--json", a->json, "Print the card and run figures as one JSON document");
  cmd->add_flag("--master-curve", a->master.enabled,
                "Data are raw isotherms: shift them to --reference-c first; the card gets WLF fitted to the shifts");
  cmd->add_option("--shifts-out", a->master.shifts_out,
                  "--master-curve/--shifts: write the isotherm shifts (pyvisco format T,log_aT)");
  cmd->add_option("--shifts", a->master.shifts_in,
                  "Raw isotherms: shift them by these factors (pyvisco T,log_aT file) instead of fitting shifts");
  cmd->callback([a, cmd] {
    FitArgs args = *a;
    args.objective_given = cmd->count("--residual") + cmd->count("--storage-weight") + cmd->count("--loss-weight") > 0;
    args.command_line = command_line();
    run_fit(args);
  });
}

}  // namespace fitcli
