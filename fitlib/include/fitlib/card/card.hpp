#pragma once
// Material cards (docs/formats.md §3): a model, its parameter values with uncertainty, how the fit
// went and where the data came from. JSON via nlohmann-json; written atomically.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fitlib/model/model.hpp"

namespace fitlib::card {

struct ParameterEstimate {
  double value = 0.0;
  bool fixed = false;
  std::optional<double> std_error;  // empty when it cannot be estimated
  std::string std_error_reason;     // why not (rank-deficient Jacobian, fixed, ...)
  std::optional<double> ci95_low, ci95_high;
};

struct Card {
  static constexpr const char* kSchema = "fitlib.card/1";
  // No card value (moduli in MPa, times in s, law constants) lies beyond this in magnitude;
  // larger ones would overflow the moduli (docs/decisions.md, "Card value range").
  static constexpr double kMaxMagnitude = 1e100;
  std::string name;
  std::string model_kind;
  nlohmann::json model_options = nlohmann::json::object();
  std::vector<ParameterEstimate> parameters;  // in the model's parameter order
  nlohmann::json fit = nlohmann::json::object();         // objective, backend, metrics, ...
  nlohmann::json provenance = nlohmann::json::object();  // data files, sha256, version, command

  // The model this card describes (make_model(model_kind, model_options)).
  model::ModelPtr model() const;
  // Parameter values in model order.
  std::vector<double> values() const;
};

// Throws core::InputError when the card's temperature law describes no material at T (°C)
// (model::Model::temperature_out_of_law): the message names the card (`card_path`), the error the
// `file` and `key` that asked for T.
void require_material_at(const Card& card, const std::string& card_path, double temperature_C,
                         const std::string& file, const std::string& key);

// "" when the card's fit passed its quality verdict (or the card records none); otherwise one line
// for a user of the card: how many warnings fit.quality.warnings holds and the first of them
// (docs/fitting.md "Quality verdict"). Said by every command that reads a card.
std::string fit_quality_warning(const Card& card);

// Reads and validates a card; InputError names the file and the offending key.
Card load_card(const std::string& path);
Card card_from_json(const nlohmann::json& j, const std::string& source = "card");
nlohmann::json card_to_json(const Card& card);
// Writes the card atomically. Output is deterministic for equal cards (fixed key order and
// number formatting); `provenance.created_utc` is whatever the caller put there.
void save_card(const std::string& path, const Card& card);

}  // namespace fitlib::card
