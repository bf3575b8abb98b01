#include "fitlib/card/fit_card.hpp"

#include <boost/algorithm/string/join.hpp>
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "fitlib/card/card.hpp"
#include "fitlib/card/conversion.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/fit/relaxation.hpp"
#include "fitlib/fit/shift_laws.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "fitlib/model/model.hpp"
#include "fitlib/model/time_series.hpp"

namespace fitlib::card {
namespace {

// --terms N (not auto), checked against the cap.
int fixed_terms(const FitCardOptions& o) {
  int n = 0;
  try {
    n = std::stoi(o.terms);
  } catch (const std::exception&) {
    throw core::UsageError("--terms takes a number or 'auto', got '" + o.terms + "'");
  }
  if (o.max_terms > 0 && n > o.max_terms)
    throw core::UsageError("--terms " + o.terms + " exceeds --max-terms " + std::to_string(o.max_terms));
  return n;
}

// The model's options: the user's, the data's mode, no law of its own when shifts give it.
nlohmann::json model_options(const FitCardOptions& o, model::TestMode mode) {
  nlohmann::json options = o.model_options;
  if (o.shifts) {
    options["temperature_law"] = "none";
    options.erase("polynomial_degree");
  }
  options["mode"] = model::to_string(mode);
  return options;
}

fit::TermOptions term_options(const FitCardOptions& o) {
  fit::TermOptions t = o.term;
  t.solver_cap = o.max_terms;
  return t;
}

// The selection's fit with its messages; the selection keeps the rest.
fit::FitResult take_result(fit::TermSelection& selection) {
  fit::FitResult result = std::move(selection.result);
  result.messages.insert(result.messages.end(), selection.messages.begin(), selection.messages.end());
  return result;
}

// The card's law fitted to the isotherm shifts (the fit itself ran at reference_C without one).
fit::FitResult with_shift_law(const FitCardOptions& o, fit::FitResult result) {
  if (!o.shifts) return result;
  const auto& s = *o.shifts;
  return fit::with_law_from_shifts(result, s.temperatures_C, s.log10_aT, s.reference_C, s.law,
                                   o.model_options.value("polynomial_degree", 3));
}

// With a law fitted to shifts: the card's figures on the measured isotherms join the verdict.
void add_measured_isotherm_verdict(const FitCardOptions& o, fit::FitResult& r) {
  if (!o.shifts) return;
  fit::QualityVerdict v;
  if (o.provenance.measured)
    v = fit::measured_isotherm_verdict(*r.model, r.values, *o.provenance.measured);
  else if (o.measured_relaxation)
    v = fit::measured_isotherm_verdict(*r.model, r.values, *o.measured_relaxation);
  r.quality.figures.insert(r.quality.figures.end(), v.figures.begin(), v.figures.end());
  r.quality.warnings.insert(r.quality.warnings.end(), v.warnings.begin(), v.warnings.end());
}

FitCardResult finish(const FitCardOptions& o, fit::FitResult result, const data::DynamicTestTable& table,
                     std::optional<fit::TermSelection> selection) {
  FitCardResult out;
  out.result = with_shift_law(o, std::move(result));
  add_measured_isotherm_verdict(o, out.result);
  out.card = card_from_fit(out.result, o.fit, table, o.provenance);
  out.selection = std::move(selection);
  out.warnings = table.warnings;
  out.warnings.insert(out.warnings.end(), out.result.quality.warnings.begin(), out.result.quality.warnings.end());
  return out;
}

// --terms auto by the spectrum fits with its own objective unless the user chose one.
bool by_spectrum(const FitCardOptions& o) {
  return o.terms == "auto" && term_options(o).method == fit::TermMethod::spectrum;
}
fit::FitOptions auto_fit_options(const FitCardOptions& o) {
  fit::FitOptions fit = o.fit;
  if (by_spectrum(o) && !o.objective_given) {
    fit.residual = fit::kSpectrumResidual;  // the default objective of --terms auto
    fit.storage_weight = fit::kSpectrumStorageWeight;
  }
  return fit;
}

// The default objective of --terms auto by the spectrum, chosen from the data (docs/fitting.md
// "Default objective"): both moduli count (relative errors, weights 1:1) when one spectrum
// follows both, i.e. when the verdict of that fit has no warning on the storage modulus (size or
// bias): the data are then Kramers–Kronig consistent to within the verdict's thresholds. Else E′
// leads (storage weight fit::kSpectrumStorageWeight) and a warning says by how much and where
// E″ is given up. `fit` becomes the options of the selection returned.
fit::TermSelection select_with_default_objective(const FitCardOptions& o, const nlohmann::json& options,
                                                 const data::DynamicTestTable& table, fit::FitOptions& fit) {
  const auto make = [&](int n) {
    nlohmann::json with_terms = options;
    with_terms["terms"] = n;
    return model::make_model(o.model, with_terms);
  };
  // The choice is made on the smooth spectra; only the one kept is compacted and capped.
  const fit::TermOptions terms = term_options(o);
  fit::TermOptions smooth = terms;
  if (fit::spectrum_applies(make)) smooth.compact.enabled = false, smooth.solver_cap = 0;
  const auto compact = [&](const fit::FitOptions& f, fit::TermSelection& sel) {
    if (sel.method == fit::TermMethod::spectrum) fit::compact_spectrum_selection(make, table, f, terms, sel);
  };
  fit::FitOptions both = fit;
  both.residual = fit::kSpectrumResidual;
  both.storage_weight = both.loss_weight = 1.0;
  fit::TermSelection balanced = fit::select_terms(make, table, both, smooth);
  const fit::FitMetrics b = balanced.result.metrics;
  const auto on_storage = [](const std::string& w) { return w.find("the storage modulus") != std::string::npos; };
  const auto& verdict = balanced.result.quality.warnings;
  if (std::none_of(verdict.begin(), verdict.end(), on_storage)) {
    fit = both;
    compact(both, balanced);
    balanced.messages.push_back("default objective: both moduli count (relative errors, weights 1:1): the data are "
                                "Kramers-Kronig consistent to within the verdict's thresholds (smooth spectrum: rms "
                                "log10 storage " + core::format_number(b.rms_log10_storage, 3) + ", loss " +
                                core::format_number(b.rms_log10_loss, 3) + ")");
    return balanced;
  }
  fit::TermSelection first = fit::select_terms(make, table, fit, smooth);
  const fit::FitMetrics e = first.result.metrics;
  compact(fit, first);
  const double cost = e.rms_log10_storage > 0.0 ? b.rms_log10_storage / e.rms_log10_storage : 1.0;
  std::ostringstream s;
  s << "with both moduli counting the storage rms log10 error is " << core::format_number(b.rms_log10_storage, 3)
    << " (x" << core::format_number(cost, 3) << " the E'-first fit's " << core::format_number(e.rms_log10_storage, 3)
    << ", loss " << core::format_number(b.rms_log10_loss, 3) << " against " << core::format_number(e.rms_log10_loss, 3)
    << ")";
  std::ostringstream w;
  w << "default objective: E' leads (relative errors, storage weight " << fit.storage_weight
    << ") because the data are not Kramers-Kronig consistent: " << s.str() << "; E'' is given up: rms log10 "
    << core::format_number(e.rms_log10_loss, 3) << " instead of " << core::format_number(b.rms_log10_loss, 3);
  const auto& ranges = first.result.quality.kramers_kronig_ranges_Hz;  // the verdict's (quality.hpp)
  for (std::size_t k = 0; k < ranges.size(); ++k)
    w << (k ? ", " : ", off by more than a factor 1.5 between ") << ranges[k].first << " and " << ranges[k].second
      << " Hz";
  w << " (--storage-weight 1 --loss-weight 1 --residual relative fits both)";
  first.result.quality.warnings.push_back(w.str());
  return first;
}

// What eval and export would say of the card: the reader's checks (card_from_json) on the JSON
// it is written as, then export's admissibility (docs/fitting.md "Round trip at fit time").
std::string read_back_problems(const Card& card) {
  Card back;
  try {
    back = card_from_json(card_to_json(card), "the card");
  } catch (const core::InputError& e) {
    return e.what();
  }
  return admissibility_problems(back);
}

// The relaxed floor (FitOptions::relaxed_floor) that lifts the relaxed modulus to 1.05 ×
// kMinRelaxedRatio × the instantaneous one; 0 when that is not the card's problem or its fit
// has no floor to raise.
double raised_relaxed_floor(const Card& card, const fit::FitOptions& o) {
  model::MaxwellSeries s;
  if (!exact_maxwell_series(*card.model(), card.values(), &s) || s.relaxed >= kMinRelaxedRatio * s.glassy())
    return 0.0;
  const double floor = card.fit.value("admissible", nlohmann::json::object()).value("relaxed_min_MPa", 0.0);
  if (!(floor > 0.0) || !(o.relaxed_floor > 0.0)) return 0.0;
  return o.relaxed_floor * 1.05 * kMinRelaxedRatio * s.glassy() / floor;
}

// Runs `run` until its card reads back: a relaxed modulus below kMinRelaxedRatio × the
// instantaneous one is refitted with the floor raised (up to 3 times); any other problem, or one
// that stays, is a NumericalError (exit 4) naming it, and nothing is written.
template <class Run>
FitCardResult read_back_checked(const FitCardOptions& o, Run run) {
  FitCardOptions used = o;
  for (int round = 0;; ++round) {
    FitCardResult r = run(used);
    const std::string problems = read_back_problems(r.card);
    if (problems.empty()) {
      if (round > 0) {
        const std::string note = "refitted with the relaxed modulus floor raised to " +
                                 core::format_number(used.fit.relaxed_floor, 4) +
                                 " x the lowest storage so that E_inf >= " + core::format_number(kMinRelaxedRatio, 3) +
                                 " x the instantaneous modulus (FE stability; export refuses less)";
        r.result.messages.push_back(note);
        r.card.fit["messages"].push_back(note);
      }
      return r;
    }
    const double floor = raised_relaxed_floor(r.card, used.fit);
    if (!(floor > 0.0) || round == 3)
      throw core::NumericalError("the card this fit would write does not read back in eval/export (" + problems +
                                 "); nothing written");
    used.fit.relaxed_floor = floor;
  }
}

}  // namespace

fit::MasterCurve refine_master_curve(const data::DynamicTestTable& raw, fit::MasterCurve curve,
                                     const FitCardOptions& o) {
  if (curve.isotherms.size() < 2 || !by_spectrum(o) || raw.rows.empty()) return curve;
  nlohmann::json options = model_options(o, raw.rows.front().condition.mode);
  options["temperature_law"] = "none";  // the master is fitted at the reference, the law comes after
  options["reference_C"] = curve.reference_C;
  if (!model::make_model(o.model, options)->options().contains("terms")) return curve;
  const auto make = [&](int n) {
    nlohmann::json with_terms = options;
    with_terms["terms"] = n;
    return model::make_model(o.model, with_terms);
  };
  fit::SpectrumOptions spectrum = term_options(o).spectrum;
  return fit::refine_shifts_with_spectrum(make, raw, std::move(curve), auto_fit_options(o), spectrum).curve;
}

FitCardResult fit_card(const data::DynamicTestTable& table, const FitCardOptions& options) {
  return read_back_checked(options, [&](const FitCardOptions& o) { return fit_card_unchecked(table, o); });
}

FitCardResult fit_relaxation_card(const data::RelaxationTable& table, const FitCardOptions& options) {
  return read_back_checked(options, [&](const FitCardOptions& o) { return fit_relaxation_card_unchecked(table, o); });
}

FitCardResult fit_card_unchecked(const data::DynamicTestTable& table, const FitCardOptions& o) {
  if (table.rows.empty()) throw core::InputError("no usable rows", boost::algorithm::join(table.source_files, " "));
  // The model describes the mode of the data unless the data mix modes.
  nlohmann::json options = model_options(o, table.rows.front().condition.mode);
  const fit::FitOptions fit = auto_fit_options(o);
  const bool has_terms = model::make_model(o.model, options)->options().contains("terms");
  if (has_terms && o.terms == "auto") {
    fit::FitOptions chosen = fit;
    auto selection = by_spectrum(o) && !o.objective_given
                         ? select_with_default_objective(o, options, table, chosen)
                         : fit::select_terms(o.model, options, table, fit, term_options(o));
    auto result = take_result(selection);
    FitCardOptions used = o;
    used.fit = chosen;
    return finish(used, std::move(result), table, std::move(selection));
  }
  if (!has_terms) return finish(o, fit::fit(model::make_model(o.model, options), table, fit), table, std::nullopt);
  const int terms = fixed_terms(o);
  const auto make = [&](int n) {
    nlohmann::json with_terms = options;
    with_terms["terms"] = n;
    return model::make_model(o.model, with_terms);
  };
  // --terms N of a series model with linear moduli (fitcli's default backend): the log grid, free
  // times only where they pay (fit/fixed_terms.hpp, docs/fitting.md "Fixed term counts").
  std::optional<fit::FitResult> fast = fit::fit_fixed_terms(make, table, fit, terms, o.fixed_terms);
  return finish(o, fast ? std::move(*fast) : fit::fit(make(terms), table, fit), table, std::nullopt);
}

FitCardResult fit_relaxation_card_unchecked(const data::RelaxationTable& table, const FitCardOptions& o) {
  if (table.rows.empty()) throw core::InputError("no usable rows", boost::algorithm::join(table.source_files, " "));
  nlohmann::json options = model_options(o, table.rows.front().mode);
  if (!model::make_model(o.model, options)->options().contains("terms"))
    throw core::UsageError("relaxation data: --model must be a series model (prony)");
  data::DynamicTestTable provenance;  // a card records its data files and their sha256
  provenance.source_files = table.source_files;
  provenance.source_sha256 = table.source_sha256;
  if (o.terms == "auto") {
    auto selection = fit::select_relaxation_terms(o.model, options, table, o.fit, term_options(o));
    auto result = take_result(selection);
    return finish(o, std::move(result), provenance, std::move(selection));
  }
  options["terms"] = fixed_terms(o);
  return finish(o, fit::fit_relaxation(model::make_model(o.model, options), table, o.fit), provenance, std::nullopt);
}

}  // namespace fitlib::card
