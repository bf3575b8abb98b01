// fitcli fit: dynamic-test tables → fitted model → material card (formats.md §3, §6).
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "fitlib/card/from_fit.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/terms.hpp"
#include "output.hpp"

namespace fitcli {
namespace {

// ---- --master-curve (fit/master_curve.hpp): raw isotherms → free per-isotherm shifts → the
// model is fitted to the master table at --reference-c; the card gets the WLF law fitted to the
// shifts (C1, C2 fixed). Shift table on stdout (stderr with --json), CSV with --shifts-out.
struct MasterCurveArgs {
  bool enabled = false;
  std::string shifts_out;
  std::optional<fitlib::fit::MasterCurve> curve;
};

fitlib::data::DynamicTestTable master_curve_table(MasterCurveArgs& m, double reference_C, bool json,
                                                  const std::string& temperature_law,
                                                  fitlib::data::DynamicTestTable raw) {
  if (!m.enabled) return raw;
  if (temperature_law != "none")
    throw fitlib::core::UsageError("--master-curve sets the card's temperature law (WLF fitted to the shifts); "
                                   "drop --temperature-law");
  fitlib::fit::MasterCurveOptions options;
  options.reference_C = reference_C;
  m.curve = fitlib::fit::build_master_curve(raw, options);
  (json ? std::cerr : std::cout) << fitlib::fit::format_shift_table(*m.curve) << "\n";
  return m.curve->master;
}
// ---- end --master-curve

struct FitArgs {
  std::vector<std::string> data;
  std::string model, terms = "4", backend = "auto", format = "native", mode, out, name;
  std::string temperature_law = "none", residual = "log10", term_rule = "bic";
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

void run_fit(FitArgs a) {
  using namespace fitlib;
  // Every output is checked before the work and written after it: no partial results.
  if (!a.out.empty()) core::check_output_path(a.out);
  if (!a.master.shifts_out.empty()) core::check_output_path(a.master.shifts_out);
  data::ReadOptions read;
  read.format = a.format == "pyvisco" ? data::TableFormat::pyvisco : data::TableFormat::native;
  read.skip_bad_rows = a.skip_bad_rows;
  if (!a.mode.empty()) {
    read.has_default_mode = true;
    read.default_mode = model::parse_test_mode(a.mode);
  }
  const auto table = master_curve_table(a.master, a.reference_C, a.json, a.temperature_law,
                                        data::read_dynamic_tables(a.data, read));
  for (const auto& w : table.warnings) std::cerr << "fitcli: warning: " << w << "\n";
  if (table.rows.empty()) throw core::InputError("no usable rows", join(a.data));

  nlohmann::json options = {{"temperature_law", a.temperature_law}, {"reference_C", a.reference_C}};
  // The model describes the mode of the data unless the data mix modes.
  const auto mode = table.rows.front().condition.mode;
  options["mode"] = model::to_string(mode);
  if (a.bulk_modulus) options["bulk_modulus"] = true;
  a.fit.backend = fit::parse_backend(a.backend);
  a.fit.record_timing = a.record_timing;
  a.fit.residual = fit::parse_residual_kind(a.residual);

  fit::FitResult result;
  std::string term_table;
  nlohmann::json terms_json;
  const bool has_terms = model::make_model(a.model, options)->options().contains("terms");
  if (has_terms && a.terms == "auto") {
    fit::TermOptions t;
    t.max_terms = a.term_search_max;
    t.solver_cap = a.max_terms;
    t.rule = fit::parse_term_rule(a.term_rule);
    auto selection = fit::select_terms(a.model, options, table, a.fit, t);
    term_table = fit::format_term_table(selection);
    terms_json = {{"by_aic", selection.by_aic}, {"by_bic", selection.by_bic}, {"by_ratio", selection.by_ratio},
                  {"rule", fit::to_string(selection.rule)}, {"chosen", selection.chosen},
                  {"unconstrained", selection.unconstrained}, {"cap_cost_ratio", selection.cap_cost_ratio},
                  {"cap_storage_rms_ratio", selection.cap_storage_rms_ratio},
                  {"cap_loss_rms_ratio", selection.cap_loss_rms_ratio}};
    terms_json["rows"] = nlohmann::json::array();
    for (const auto& row : selection.rows)
      terms_json["rows"].push_back({{"terms", row.terms}, {"wall_time_s", row.wall_time_s},
                                    {"rms_log10_storage", row.rms_log10_storage},
                                    {"rms_log10_loss", row.rms_log10_loss}, {"cost", row.cost},
                                    {"aic", row.aic}, {"bic", row.bic}, {"failed", row.failed}});
    for (const auto& m : selection.messages) result.messages.push_back(m);
    auto msgs = result.messages;
    result = selection.result;
    result.messages.insert(result.messages.end(), msgs.begin(), msgs.end());
  } else {
    if (has_terms) {
      int n = 0;
      try {
        n = std::stoi(a.terms);
      } catch (const std::exception&) {
        throw core::UsageError("--terms takes a number or 'auto', got '" + a.terms + "'");
      }
      if (a.max_terms > 0 && n > a.max_terms)
        throw core::UsageError("--terms " + a.terms + " exceeds --max-terms " + std::to_string(a.max_terms));
      options["terms"] = n;
    }
    result = fit::fit(model::make_model(a.model, options), table, a.fit);
  }
  if (a.master.curve) result = fit::with_wlf_from_shifts(result, *a.master.curve);  // --master-curve
  const auto card = card::card_from_fit(
      result, a.fit, table, {a.name.empty() ? a.model + "-fit" : a.name, a.command_line, a.record_timing});
  if (!a.out.empty()) card::save_card(a.out, card);
  if (!a.master.shifts_out.empty() && a.master.curve)
    core::write_file_atomically(a.master.shifts_out, fit::shift_table_csv(*a.master.curve));

  if (a.json) {
    auto j = card::card_to_json(card);
    if (a.record_timing) j["fit"]["wall_time_s"] = result.metrics.wall_time_s;
    if (!terms_json.is_null()) j["term_selection"] = terms_json;
    std::cout << j.dump(2) << "\n";
    return;
  }
  const auto& m = result.metrics;
  if (!term_table.empty()) std::cout << term_table << "\n";
  std::cout << "model " << card.model_kind << " (" << card.model_options.dump() << "), backend "
            << result.backend_used << "\n";
  std::cout << "points " << m.n_points << ", free parameters " << m.n_free << ", converged "
            << (m.converged ? "yes" : "no") << ", wall time " << m.wall_time_s * 1e3 << " ms\n";
  std::cout << "rms log10 error: storage " << m.rms_log10_storage << ", loss " << m.rms_log10_loss
            << "; relative error mean " << m.mean_rel_error << ", max " << m.max_rel_error << "\n";
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
  cmd->add_option("--backend", a->backend, "auto | nnls | ceres | nlopt | staged")->capture_default_str();
  cmd->add_option("--format", a->format, "native | pyvisco")->capture_default_str()
      ->check(CLI::IsMember({"native", "pyvisco"}));
  cmd->add_option("--mode", a->mode, "Test mode for files without a mode column (shear | uniaxial | bulk)");
  cmd->add_option("--temperature-law", a->temperature_law, "none | wlf | arrhenius")->capture_default_str();
  cmd->add_option("--reference-c", a->reference_C, "Reference temperature, degC")->capture_default_str();
  cmd->add_flag("--bulk-modulus", a->bulk_modulus, "Add a constant bulk modulus K (mode conversion)");
  cmd->add_option("--residual", a->residual, "log10 | relative")->capture_default_str()
      ->check(CLI::IsMember({"log10", "relative"}));
  cmd->add_option("--storage-weight", a->fit.storage_weight, "Weight of storage-modulus residuals")
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
  cmd->add_option("--shifts-out", a->master.shifts_out, "--master-curve: write the shift table (CSV)");
  cmd->callback([a] {
    FitArgs args = *a;
    args.command_line = command_line();
    run_fit(args);
  });
}

}  // namespace fitcli
