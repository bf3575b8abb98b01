#pragma once
// Hyperelastic cards (docs/hyperelastic.md): quasi-static rows → fit → card, and the FE keywords
// of a hyperelastic card (Abaqus/CalculiX *HYPERELASTIC, ANSYS TB,HYPER, LS-DYNA MAT_027/MAT_077_O),
// each with its convention for Ogden's μ and the volumetric term stated in the deck.
#include <string>

#include <nlohmann/json.hpp>

#include "fitlib/card/card.hpp"
#include "fitlib/card/export.hpp"
#include "fitlib/data/quasi_static.hpp"
#include "fitlib/fit/hyperelastic.hpp"

namespace fitlib::card {

struct HyperelasticCardOptions {
  std::string model;                                       // a hyperelastic kind
  nlohmann::json model_options = nlohmann::json::object();  // terms, compressible
  fit::HyperelasticFitOptions fit;
  std::string name, command;
};

struct HyperelasticCardResult {
  Card card;
  fit::HyperelasticFitResult result;
};

HyperelasticCardResult fit_hyperelastic_card(const data::QuasiStaticTable& table, const HyperelasticCardOptions& options);

// The figures and findings as stored in a card's fit.quality / fit.stability.
nlohmann::json figures_json(const std::vector<fit::ModeFigure>& figures);

// The visco-hyperelastic card of a hyperelastic `base` (its long-term response) and the Prony
// series of a shear card `prony` (any model with an exact Maxwell series at its reference
// temperature): g_i = G_i/G0 of that series, τ_i as fitted. UsageError when `prony` has none.
Card visco_hyperelastic_card(const Card& base, const Card& prony, const std::string& name);

// Keywords of a hyperelastic card; UsageError for what a format cannot hold (Gent in Abaqus,
// Ogden beyond 6 terms in Abaqus/ANSYS or 8 in LS-DYNA, laws LS-DYNA lacks). An incompressible
// card gets D1 = 2/K with K from options.poisson_ratio and μ0 (said in the deck).
std::string export_hyperelastic(const Card& card, const std::string& format, const ExportOptions& options);

}  // namespace fitlib::card
