#pragma once
// Table → card in one call: the model's options from the data, the fit (or the term selection of
// --terms auto), the temperature law fitted to given isotherm shifts, the quality verdict and the
// card (docs/fitting.md). fitcli fit and the Python module's fit_card both call it.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/card/from_fit.hpp"
#include "fitlib/data/relaxation.hpp"
#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/fixed_terms.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/terms.hpp"

namespace fitlib::card {

// Isotherm shifts (temperature, log10 a_T) whose law the card gets: the data were shifted to
// reference_C before the fit (master curve, or given shift factors).
struct IsothermShifts {
  double reference_C = 0.0;
  std::vector<double> temperatures_C, log10_aT;
  model::ShiftLaw law = model::ShiftLaw::wlf;  // wlf | polynomial
};

struct FitCardOptions {
  std::string model;       // model kind (model::make_model)
  std::string terms = "4";  // series models: a number, or "auto" (term selection)
  int max_terms = 0;        // solver cap on terms (0: none); --terms N above it is refused
  // temperature_law, reference_C, polynomial_degree, bulk_modulus; "mode" comes from the data.
  nlohmann::json model_options = nlohmann::json::object();
  fit::FitOptions fit;
  fit::TermOptions term;  // --terms auto (its solver_cap is max_terms)
  fit::FixedTermOptions fixed_terms;  // --terms N of a series model (fit/fixed_terms.hpp)
  // The user chose the residual or the weights: --terms auto by the spectrum keeps them instead
  // of its own objective (fit::kSpectrumResidual, fit::kSpectrumStorageWeight).
  bool objective_given = false;
  std::optional<IsothermShifts> shifts;
  CardProvenance provenance;
  // Relaxation isotherms before their shifts: with `shifts`, the verdict adds the card's errors on
  // them (fit::measured_isotherm_verdict), as provenance.measured does for frequency data.
  const data::RelaxationTable* measured_relaxation = nullptr;
};

struct FitCardResult {
  Card card;
  fit::FitResult result;
  std::optional<fit::TermSelection> selection;  // --terms auto (its result moved into `result`)
  std::vector<std::string> warnings;            // the table's, then the quality verdict's
};

// Frequency-domain rows (non-empty; InputError otherwise, naming the files). The card is read
// back through the checks of eval and export before it is returned (docs/fitting.md "Round trip
// at fit time"): a relaxed modulus below export's ratio is refitted with a raised floor; a card
// that still fails is a core::NumericalError naming why.
FitCardResult fit_card(const data::DynamicTestTable& table, const FitCardOptions& options);
// The same without the read-back check (tests that show what the check catches).
FitCardResult fit_card_unchecked(const data::DynamicTestTable& table, const FitCardOptions& options);

// Raw isotherms with --terms auto by the spectrum: the isotherm shifts of `curve` (pairwise) and
// the spectrum refined together (fit::refine_shifts_with_spectrum, docs/fitting.md); `curve`
// unchanged for a fixed number of terms, the sweep, or a model without terms. `fit_card` on the
// result's master then fits the card.
fit::MasterCurve refine_master_curve(const data::DynamicTestTable& raw, fit::MasterCurve curve,
                                     const FitCardOptions& options);

// Relaxation rows (t, M(t)); the model must be a series model (UsageError otherwise).
FitCardResult fit_relaxation_card(const data::RelaxationTable& table, const FitCardOptions& options);
FitCardResult fit_relaxation_card_unchecked(const data::RelaxationTable& table, const FitCardOptions& options);

}  // namespace fitlib::card
