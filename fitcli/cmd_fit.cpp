// fitcli fit: dynamic-test tables → fitted model → material card (docs/formats.md §3, §6).
#include <algorithm>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.hpp"
#include "fitlib/card/fit_card.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/quasi_static.hpp"
#include "fitlib/data/relaxation.hpp"
#include "fitlib/data/shift_factors.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/shift_laws.hpp"
#include "fitlib/fit/terms.hpp"
#include "fitlib/model/hyperelastic.hpp"
#include "fitlib/model/linear.hpp"
#include "hyperelastic.hpp"
#include "inputs.hpp"
#include "output.hpp"
#include "plot.hpp"

namespace fitcli {
namespace {

// ---- --master-curve (fit/master_curve.hpp): raw isotherms → free per-isotherm shifts (with
// --terms auto refined with the spectrum, card::refine_master_curve) → the model is fitted to
// the master table at --reference-c; the card gets the WLF law fitted to the
// shifts (C1, C2 fixed). Shift table with the summary (stderr with --json), CSV with --shifts-out.
struct MasterCurveArgs {
  bool enabled = false;
  std::string shifts_out;
  std::string shifts_in;  // --shifts: given shift factors (pyvisco file) instead of fitted ones
  std::optional<fitlib::fit::MasterCurve> curve;
};

// The isotherm shift table: on the summary, or on stderr beside --json.
void print_shift_table(const fitlib::fit::MasterCurve& curve, bool json) {
  const std::string table = fitlib::fit::format_shift_table(curve) + "\n";
  if (!json) summary() << table;
  else if (!quiet()) std::cerr << table;
}

fitlib::data::DynamicTestTable master_curve_table(MasterCurveArgs& m, double reference_C, bool json,
                                                  const std::string& temperature_law,
                                                  const fitlib::data::DynamicTestTable& raw,
                                                  const fitlib::card::FitCardOptions& card_options) {
  if (!m.enabled && m.shifts_in.empty()) return raw;
  if (temperature_law != "none" && temperature_law != "wlf" && temperature_law != "polynomial")
    throw fitlib::core::UsageError("--master-curve/--shifts fit the card's temperature law to the shifts: "
                                   "--temperature-law wlf (default) or polynomial");
  if (!m.shifts_in.empty()) {
    m.curve = fitlib::fit::master_curve_from_shift_factors(raw, fitlib::data::read_shift_factors(input_path(m.shifts_in)),
                                                           reference_C);
  } else {
    fitlib::fit::MasterCurveOptions options;
    options.reference_C = reference_C;
    m.curve = fitlib::card::refine_master_curve(raw, fitlib::fit::build_master_curve(raw, options), card_options);
  }
  print_shift_table(*m.curve, json);
  return m.curve->master;
}
// ---- end --master-curve

struct FitArgs {
  std::vector<std::string> data;
  std::string model, terms = "4", backend = "auto", format = "native", mode, out, name, plot;
  std::string temperature_law = "none", residual = "log10", term_rule = "bic", term_method = "spectrum";
  double smoothness = -1.0, terms_per_decade = 2.0;  // --terms auto, method spectrum
  bool objective_given = false;  // --residual, --storage-weight or --loss-weight on the command line
  int polynomial_degree = 3;
  double reference_C = 23.0;
  bool bulk_modulus = false, skip_bad_rows = false, json = false, record_timing = false;
  int max_terms = 0, term_search_max = 0;
  fitlib::fit::FitOptions fit;
  fitlib::fit::FixedTermOptions fixed_terms;  // --terms N (--polish-iterations)
  std::string command_line;
  MasterCurveArgs master;  // --master-curve
  HyperelasticFitArgs hyper;  // a hyperelastic --model: quasi-static tables (hyperelastic.hpp)
};

// The command line as library options (card/fit_card.hpp); `shifts` from --master-curve/--shifts.
fitlib::card::FitCardOptions fit_card_options(const FitArgs& a) {
  using namespace fitlib;
  card::FitCardOptions o;
  o.model = a.model;
  o.terms = a.terms;
  o.max_terms = a.max_terms;
  o.model_options = {{"temperature_law", a.temperature_law}, {"reference_C", a.reference_C}};
  if (a.temperature_law == "polynomial") o.model_options["polynomial_degree"] = a.polynomial_degree;
  if (a.bulk_modulus) o.model_options["bulk_modulus"] = true;
  o.fit = a.fit;
  o.fit.backend = fit::parse_backend(a.backend);
  o.fit.record_timing = a.record_timing;
  o.fit.residual = fit::parse_residual_kind(a.residual);
  o.term.max_terms = a.term_search_max;
  o.fixed_terms = a.fixed_terms;
  o.term.rule = fit::parse_term_rule(a.term_rule);
  o.term.method = fit::parse_term_method(a.term_method);
  o.term.spectrum.lambda = a.smoothness;
  o.term.spectrum.per_decade = a.terms_per_decade;
  o.term.spectrum.polish = a.fit.polish;
  o.objective_given = a.objective_given;
  o.provenance = {a.name.empty() ? a.model + "-fit" : a.name, a.command_line, a.record_timing};
  return o;
}

fitlib::card::IsothermShifts isotherm_shifts(const FitArgs& a, const fitlib::fit::MasterCurve& curve) {
  fitlib::card::IsothermShifts s;
  s.reference_C = curve.reference_C;
  for (const auto& iso : curve.isotherms) {
    s.temperatures_C.push_back(iso.temperature_C);
    s.log10_aT.push_back(iso.log10_aT);
  }
  s.law = a.temperature_law == "polynomial" ? fitlib::model::ShiftLaw::polynomial : fitlib::model::ShiftLaw::wlf;
  return s;
}

// The term table of --terms auto as JSON.
nlohmann::json selection_json(const fitlib::fit::TermSelection& selection) {
  nlohmann::json json = {{"by_aic", selection.by_aic}, {"by_bic", selection.by_bic}, {"by_ratio", selection.by_ratio},
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
  return json;
}

// Human summary of the fit (stdout, or stderr when the card goes to stdout).
void print_summary(const FitArgs& a, const fitlib::card::FitCardResult& r) {
  const auto& result = r.result;
  const auto& m = result.metrics;
  std::ostream& out = summary();
  if (r.selection) out << fitlib::fit::format_term_table(*r.selection) << "\n";
  out << "model " << r.card.model_kind << " (" << r.card.model_options.dump() << "), backend "
      << result.backend_used << "\n";
  out << "points " << m.n_points << ", free parameters " << m.n_free << ", converged "
      << (m.converged ? "yes" : "no") << ", wall time " << m.wall_time_s * 1e3 << " ms\n";
  // Relaxation data: one modulus, M(t), its worst row a time (the figure's frequency is 1/(2π t)).
  const auto& figures = result.quality.figures;
  const bool relaxation = !figures.empty() && figures.front().modulus == "relaxation";
  if (relaxation) out << "rms log10 error of M(t) " << m.rms_log10_storage;
  else out << "rms log10 error: storage " << m.rms_log10_storage << ", loss " << m.rms_log10_loss;
  out << "; relative error mean " << m.mean_rel_error << ", max " << m.max_rel_error << "\n";
  for (const auto& f : figures) {
    out << "  " << f.modulus << " (" << f.group << "): mean relative error " << 100.0 * f.mean_rel_error
        << " %, max " << 100.0 * f.max_rel_error << " % at ";
    if (f.modulus == "relaxation") out << "t = " << 1.0 / (2.0 * M_PI * f.max_at_frequency_Hz) << " s\n";
    else out << f.max_at_frequency_Hz << " Hz\n";
  }
  const auto cost = fitlib::card::fe_cost(*result.model, result.values);
  if (cost.terms > 0)
    out << "FE cost: " << cost.terms << " terms, " << cost.state_variables
        << " state variables per integration point (3-D solid)\n";
  out << "verdict: "
      << (result.quality.acceptable() ? "within the thresholds (docs/fitting.md)"
                                      : std::to_string(result.quality.warnings.size()) + " warning(s) on stderr")
      << "\n";
  // A reason repeated down the list (a relaxation fit's, on each of 28 terms) is said once per run.
  const std::string* previous = nullptr;
  for (const auto& p : result.parameters) {
    out << "  " << p.name << " = " << exact(p.value) << " " << p.unit;
    if (p.std_error)
      out << "  ± " << *p.std_error << "  [95 %: " << *p.ci95_low << ", " << *p.ci95_high << "]";
    else if (!p.reason.empty())
      out << "  (" << (previous && *previous == p.reason ? "as above" : p.reason) << ")";
    previous = p.std_error ? nullptr : &p.reason;
    out << "\n";
  }
  for (const auto& msg : result.messages) note(msg);
  if (!a.out.empty() && a.out != "-") out << "card written to " << a.out << "\n";
}

// Writes the card (--out), the shifts (--shifts-out) and the figure (--plot), then prints the
// summary or, with --json, the card and run figures.
void finish(const FitArgs& a, fitlib::card::FitCardResult r, const std::vector<std::string>& data) {
  using namespace fitlib;
  auto& files = r.card.provenance["data_files"];
  for (auto& f : files) f = with_stdin_named(f.get<std::string>());
  if (!a.out.empty()) emit_with(a.out, [&](const std::string& path) { card::save_card(path, r.card); });
  if (!a.master.shifts_out.empty() && a.master.curve)
    emit(a.master.shifts_out, data::format_shift_factors(fit::shift_factors_of(*a.master.curve)));
  if (!a.plot.empty()) draw_figure(a.plot, [&] { plot_card(r.card, data, a.format, "", a.plot); });
  for (const auto& w : r.warnings) warning(w);

  if (a.json) {
    auto j = card::card_to_json(r.card);
    if (a.record_timing) j["fit"]["wall_time_s"] = r.result.metrics.wall_time_s;
    if (r.selection) j["term_selection"] = selection_json(*r.selection);
    std::cout << j.dump(2) << "\n";
    return;
  }
  print_summary(a, r);
}

void run_fit(FitArgs a) {
  using namespace fitlib;
  // Every output is checked before the work and written after it: no partial results.
  claim_output("--out", a.out, a.json);
  claim_output("--shifts-out", a.master.shifts_out, a.json);
  if (!a.plot.empty()) claim_png("--plot", a.plot);
  if (quiet()) a.fit.progress = false;
  const auto data = input_paths(a.data);
  for (const auto& d : data)  // a quasi-static table read as dynamic data would fail at its columns
    if (data::looks_like_quasi_static_csv(core::read_file(d)))
      throw core::UsageError(with_stdin_named(d) + " is a quasi-static table (docs/formats.md §7): fit it with a "
                             "hyperelastic --model (neo-hooke, mooney-rivlin, yeoh, reduced-polynomial, ogden, "
                             "arruda-boyce, gent)");
  if (!a.fit.schedule_path.empty()) a.fit.schedule_path = input_path(a.fit.schedule_path);
  auto options = fit_card_options(a);
  if (is_relaxation_data(data, a.format)) {
    data::RelaxationTable table = read_relaxation_tables(data);
    std::optional<data::RelaxationTable> measured;  // the isotherms before their shifts
    if (a.master.enabled || !a.master.shifts_in.empty()) {
      measured = table;
      data::ShiftFactorTable given;
      if (a.master.shifts_in.empty()) {  // model-free shifts of the isotherms, then as given shifts
        // (--shifts wins over --master-curve, as for frequency data; it was ignored here)
        fit::MasterCurveOptions mo;
        mo.reference_C = a.reference_C;
        a.master.curve = fit::build_relaxation_master_curve(table, mo);
        print_shift_table(*a.master.curve, a.json);
        given = fit::shift_factors_of(*a.master.curve);
      } else {
        given = data::read_shift_factors(input_path(a.master.shifts_in));
      }
      table = fit::shift_relaxation_table(table, given, a.reference_C);
      card::IsothermShifts s;
      s.reference_C = a.reference_C;
      for (const auto& f : given.factors) {
        s.temperatures_C.push_back(f.temperature_C);
        s.log10_aT.push_back(fit::given_log10_aT(given, f.temperature_C, a.reference_C));
      }
      s.law = a.temperature_law == "polynomial" ? model::ShiftLaw::polynomial : model::ShiftLaw::wlf;
      options.shifts = s;
      options.measured_relaxation = &*measured;
    }
    return finish(a, card::fit_relaxation_card(table, options), data);
  }
  data::ReadOptions read;
  read.format = a.format == "pyvisco" ? data::TableFormat::pyvisco : data::TableFormat::native;
  read.skip_bad_rows = a.skip_bad_rows;
  if (!a.mode.empty()) {
    read.has_default_mode = true;
    read.default_mode = model::parse_test_mode(a.mode);
  }
  const auto raw = read_tables(data, a.format, read);
  const auto table = master_curve_table(a.master, a.reference_C, a.json, a.temperature_law, raw, options);
  if (a.master.curve) {
    options.shifts = isotherm_shifts(a, *a.master.curve);
    options.provenance.measured = &raw;  // the data window of the measured isotherms
  }
  finish(a, card::fit_card(table, options), data);
}

// A hyperelastic --model: the options that apply to quasi-static fits, the rest refused.
void run_hyperelastic(const FitArgs& a, const CLI::App& cmd) {
  for (const char* dynamic : {"--temperature-law", "--master-curve", "--shifts", "--bulk-modulus", "--backend",
                              "--storage-weight", "--loss-weight", "--mean-weight", "--mode", "--format"})
    if (cmd.count(dynamic))
      throw fitlib::core::UsageError(std::string(dynamic) + " applies to dynamic-test fits, not to the hyperelastic model '" +
                                     a.model + "'");
  HyperelasticFitArgs h = a.hyper;
  h.data = a.data, h.model = a.model, h.out = a.out, h.name = a.name, h.plot = a.plot, h.json = a.json;
  h.command_line = command_line();
  if (cmd.count("--residual")) h.residual = a.residual;
  if (cmd.count("--terms")) {
    if (a.terms.empty() || a.terms.find_first_not_of("0123456789") != std::string::npos)
      throw fitlib::core::UsageError("--terms: a hyperelastic model takes a number of terms, not '" + a.terms + "'");
    h.terms = std::stoi(a.terms);
  }
  if (cmd.count("--multistart")) h.multistart = a.fit.multistart;
  h.max_iterations = a.fit.max_iterations;
  h.seed = a.fit.seed;
  run_hyperelastic_fit(h);
}

}  // namespace

void register_fit(CLI::App& app) {
  auto a = std::make_shared<FitArgs>();
  auto* cmd = app.add_subcommand("fit", "Fit a model to dynamic-test tables and write a material card");
  cmd->add_option("--data", a->data, "Data file(s): dynamic-test CSV, pyvisco CSV, EPLEXOR .xls (- = stdin)")
      ->required();
  cmd->add_option("--model", a->model,
                  "prony | zener3 | retardation | fractional-zener | fritzson | fritzson-iso; quasi-static tables: "
                  "neo-hooke | mooney-rivlin | yeoh | reduced-polynomial | ogden | arruda-boyce | gent")
      ->required();
  cmd->add_option("--terms", a->terms, "Number of terms, or 'auto' (AIC, BIC and pyvisco's rule)")
      ->capture_default_str();
  cmd->add_option("--max-terms", a->max_terms,
                  "Solver cap on terms, reporting its cost; export limits: " + export_formats_text())
      ->check(number_in(1, fitlib::model::kMaxSeriesTerms));
  cmd->add_option("--polish-iterations", a->fixed_terms.polish_iterations,
                  "--terms N below 2 terms per decade of data: iteration budget of the free-time polish (kept only when "
                  "it lowers the cost by 1 %)")
      ->capture_default_str()->check(number_in(1, 100000));
  cmd->add_option("--term-search-max", a->term_search_max, "Largest N tried by --terms auto (0: from the data)")
      ->check(number_in(0, fitlib::model::kMaxSeriesTerms));
  cmd->add_option("--term-rule", a->term_rule, "Rule that picks N for --terms auto: bic | aic | ratio")
      ->capture_default_str();
  cmd->add_option("--term-method", a->term_method,
                  "--terms auto: spectrum (smooth spectrum, GCV; series models, any temperature law; with --master-curve the shifts are refined with it) | sweep")
      ->capture_default_str()->check(CLI::IsMember({"spectrum", "sweep"}));
  cmd->add_option("--smoothness", a->smoothness,
                  "Spectrum: second-difference penalty weight lambda (default: chosen by GCV)")
      ->check(non_negative_number());
  cmd->add_option("--terms-per-decade", a->terms_per_decade, "Spectrum: time constants per decade")
      ->capture_default_str()->check(number_in(0.25, 20.0));
  cmd->add_option("--backend", a->backend, "auto | nnls | ceres | nlopt | staged")->capture_default_str();
  cmd->add_option("--format", a->format,
                  "native | pyvisco (t, E_relax files are relaxation data) | eplexor (.xls, also recognised by content)")
      ->capture_default_str()->check(CLI::IsMember({"native", "pyvisco", "eplexor"}));
  cmd->add_option("--mode", a->mode, "Test mode for files without a mode column (shear | uniaxial | bulk)");
  cmd->add_option("--temperature-law", a->temperature_law, "none | wlf | arrhenius | polynomial")->capture_default_str();
  cmd->add_option("--polynomial-degree", a->polynomial_degree, "Degree of the polynomial shift law (1..6)")
      ->capture_default_str()->check(number_in(1, fitlib::model::kMaxShiftPolynomialDegree));
  cmd->add_option("--reference-c", a->reference_C, "Reference temperature, degC")
      ->capture_default_str()->check(temperature_c_range());
  cmd->add_flag("--bulk-modulus", a->bulk_modulus, "Add a constant bulk modulus K (mode conversion)");
  cmd->add_option("--residual", a->residual,
                  "log10 | relative | complex (errors relative to |E*|); hyperelastic: relative (default) | absolute")
      ->capture_default_str()->check(CLI::IsMember({"log10", "relative", "complex", "absolute"}));
  cmd->add_option("--storage-weight", a->fit.storage_weight,
                  "Weight of storage-modulus residuals (--terms auto default: 80, with --residual relative)")
      ->capture_default_str();
  cmd->add_option("--loss-weight", a->fit.loss_weight, "Weight of loss-modulus residuals")->capture_default_str();
  cmd->add_option("--mean-weight", a->fit.mean_weight, "Weight of mean-modulus residuals")->capture_default_str();
  cmd->add_option("--fixed", a->fit.fixed, "Parameters held at their start value")->delimiter(',');
  cmd->add_option("--multistart", a->fit.multistart, "Global starts (nlopt)")
      ->capture_default_str()->check(number_in(1, 1e4));
  cmd->add_option("--tolerance", a->fit.tolerance, "Relative function tolerance")
      ->capture_default_str()->check(number_in(0, 1));
  cmd->add_option("--max-iterations", a->fit.max_iterations, "Iteration limit per solve")
      ->capture_default_str()->check(number_in(1, 1e6));
  cmd->add_option("--seed", a->fit.seed, "Random seed (multistart)")->capture_default_str();
  cmd->add_option("--schedule", a->fit.schedule_path,
                  "Staged backend: schedule file of parameter groups (JSON or TOML)");
  cmd->add_flag("--global", a->fit.global, "auto backend: run the NLopt multistart before Ceres");
  cmd->add_flag("!--no-polish", a->fit.polish, "nnls backend: keep the pure linear solve (no log-space polish)");
  cmd->add_flag("--skip-bad-rows", a->skip_bad_rows, "Skip bad rows with a listed warning instead of failing");
  cmd->add_option("--out", a->out, "Card file to write (JSON, atomically; - = stdout)");
  cmd->add_option("--plot", a->plot, "Also write the figure of fitcli plot (PNG file) after the card");
  cmd->add_option("--name", a->name, "Material name in the card (default: MODEL-fit)");
  cmd->add_flag("--record-timing", a->record_timing, "Store the wall time in the card (breaks byte-identity)");
  a->fit.progress = true;  // shown only when stderr is a terminal
  cmd->add_flag("!--no-progress", a->fit.progress, "Hide the progress of multistart runs on stderr");
  add_json_flag(cmd, a->json, "the card and run figures, on stdout");
  add_verbosity_flags(cmd);
  cmd->add_flag("--master-curve", a->master.enabled,
                "Data are raw isotherms: shift them to --reference-c first; the card gets WLF fitted to the shifts");
  cmd->add_option("--shifts-out", a->master.shifts_out,
                  "--master-curve/--shifts: shift file to write (pyvisco format T,log_aT)");
  cmd->add_option("--shifts", a->master.shifts_in,
                  "Raw isotherms: shift them by the factors of this file (pyvisco T,log_aT) instead of fitting shifts");
  cmd->add_flag("--compressible", a->hyper.compressible,
                "Hyperelastic models: add D1 (1/MPa), fitted to the volumetric rows");
  cmd->add_option("--mode-weight", a->hyper.mode_weights,
                  "Hyperelastic models: weight of a test mode's residuals, MODE=WEIGHT (repeatable)");
  cmd->add_option("--stability-range", a->hyper.stability_range,
                  "Hyperelastic models: Drucker check from MIN to MAX stretch (default 0.1,10)")
      ->delimiter(',')->expected(2);
  cmd->callback([a, cmd] {
    if (fitlib::model::is_hyperelastic_kind(a->model)) return run_hyperelastic(*a, *cmd);
    FitArgs args = *a;
    args.objective_given = cmd->count("--residual") + cmd->count("--storage-weight") + cmd->count("--loss-weight") > 0;
    args.command_line = command_line();
    run_fit(args);
  });
}

}  // namespace fitcli
