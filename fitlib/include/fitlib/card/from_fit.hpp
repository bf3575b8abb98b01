#pragma once
// A material card from a finished fit: values with their uncertainty, the fit's figures and
// identifiability, and provenance of the data.
#include <string>

#include "fitlib/card/card.hpp"
#include "fitlib/data/table.hpp"
#include "fitlib/fit/fit.hpp"

namespace fitlib::card {

struct CardProvenance {
  std::string name;     // material name in the card
  std::string command;  // the invocation, as typed
  // Wall time differs run to run; it enters the card only on request so that the same input
  // and seed give the same bytes (docs/decisions.md).
  bool record_timing = false;
  // The measured rows whose conditions make the card's data window (card/data_window.hpp) when
  // the fitted table is not them (a master curve); null: the fitted table's own rows.
  const data::DynamicTestTable* measured = nullptr;
};

Card card_from_fit(const fit::FitResult& result, const fit::FitOptions& options,
                   const data::DynamicTestTable& table, const CardProvenance& provenance);

// What the card costs an FE model (card "fit.fe_cost", the fit summary): its active series terms
// and the state variables they add at every integration point of a 3-D solid — one symmetric
// stress tensor (6 numbers) per term and relaxing part, deviatoric, plus volumetric when the
// bulk relaxes too (a uniaxial card without K, exported with one set of weights). 0 terms: none.
struct FeCost {
  int terms = 0;
  int state_variables = 0;
};
FeCost fe_cost(const model::Model& model, const std::vector<double>& values);

// The admissible window as stored in a card's "fit.admissible" (export checks a card against it).
nlohmann::json admissible_to_json(const fit::AdmissibleWindow& window);

}  // namespace fitlib::card
