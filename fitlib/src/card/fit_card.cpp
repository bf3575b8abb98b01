#include "fitlib/card/fit_card.hpp"

#include <boost/algorithm/string/join.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/fit/relaxation.hpp"
#include "fitlib/fit/shift_laws.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "fitlib/model/model.hpp"

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

FitCardResult fit_card(const data::DynamicTestTable& table, const FitCardOptions& o) {
  if (table.rows.empty()) throw core::InputError("no usable rows", boost::algorithm::join(table.source_files, " "));
  // The model describes the mode of the data unless the data mix modes.
  nlohmann::json options = model_options(o, table.rows.front().condition.mode);
  const fit::FitOptions fit = auto_fit_options(o);
  const bool has_terms = model::make_model(o.model, options)->options().contains("terms");
  if (has_terms && o.terms == "auto") {
    auto selection = fit::select_terms(o.model, options, table, fit, term_options(o));
    auto result = take_result(selection);
    FitCardOptions used = o;
    used.fit = fit;
    return finish(used, std::move(result), table, std::move(selection));
  }
  if (has_terms) options["terms"] = fixed_terms(o);
  return finish(o, fit::fit(model::make_model(o.model, options), table, fit), table, std::nullopt);
}

FitCardResult fit_relaxation_card(const data::RelaxationTable& table, const FitCardOptions& o) {
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
