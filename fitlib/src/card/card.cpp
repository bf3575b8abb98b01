#include "fitlib/card/card.hpp"

#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/io.hpp"
#include "fitlib/core/json.hpp"

namespace fitlib::card {

using nlohmann::json;

model::ModelPtr Card::model() const { return model::make_model(model_kind, model_options); }

std::vector<double> Card::values() const {
  std::vector<double> v;
  for (const auto& p : parameters) v.push_back(p.value);
  return v;
}

std::string fit_quality_warning(const Card& card) {
  const nlohmann::json* q = card.fit.contains("quality") ? &card.fit.at("quality") : nullptr;
  if (!q || !q->is_object() || !q->contains("warnings") || !q->at("warnings").is_array() ||
      q->at("warnings").empty())
    return "";
  const nlohmann::json& w = q->at("warnings");
  const std::string first = w.front().is_string() ? w.front().get<std::string>() : w.front().dump();
  return "the card's fit did not pass its quality verdict (" + std::to_string(w.size()) +
         " warning(s) in fit.quality.warnings; the first: " + first + ")";
}

void require_material_at(const Card& card, const std::string& card_path, double temperature_C,
                         const std::string& file, const std::string& key) {
  const std::string why = card.model()->temperature_out_of_law(card.values().data(), temperature_C);
  if (!why.empty()) throw core::InputError((file == card_path ? "" : "card " + card_path + ": ") + why, file, 0, 0, key);
}

json card_to_json(const Card& card) {
  const auto m = card.model();
  const auto& specs = m->parameters();
  json params = json::array();
  for (size_t i = 0; i < card.parameters.size(); ++i) {
    const auto& e = card.parameters[i];
    json p = json::object();
    p["name"] = specs[i].name;
    p["value"] = e.value;
    p["unit"] = specs[i].unit;
    p["group"] = specs[i].group;
    p["fixed"] = e.fixed;
    // No interval (docs/decisions.md "A missing interval"): std_error null, a reason, no ci95.
    const bool interval = e.std_error && e.ci95_low && e.ci95_high && std::isfinite(*e.std_error) &&
                          std::isfinite(*e.ci95_low) && std::isfinite(*e.ci95_high);
    p["std_error"] = interval ? json(*e.std_error) : json(nullptr);
    if (!interval) p["std_error_reason"] = e.std_error_reason.empty() ? "not estimated" : e.std_error_reason;
    if (interval) p["ci95"] = json::array({*e.ci95_low, *e.ci95_high});
    params.push_back(p);
  }
  const auto values = card.values();
  json j = json::object();
  j["schema"] = Card::kSchema;
  j["name"] = card.name;
  j["model"] = card.model_kind;
  j["options"] = m->options();
  j["parameters"] = params;
  j["temperature"] = m->temperature_law(values.data());
  j["fit"] = card.fit;
  j["provenance"] = card.provenance;
  return j;
}

namespace {

const json& required(const json& j, const std::string& key, const std::string& source,
                     const std::string& path) {
  if (!j.is_object() || !j.contains(key))
    throw core::InputError("missing required key", source, 0, 0, path + key);
  return j.at(key);
}

json object_or_empty(const json& j, const std::string& key, const std::string& source) {
  if (!j.contains(key)) return json::object();
  if (!j.at(key).is_object()) throw core::InputError("expected an object", source, 0, 0, key);
  return j.at(key);
}

// The card's model from its kind and options; option errors name "options".
model::ModelPtr model_of(const Card& card, const std::string& source) {
  try {
    return card.model();
  } catch (const core::UsageError& e) {
    throw core::InputError(e.what(), source, 0, 0, "options");
  } catch (const json::exception&) {
    throw core::InputError("an option has the wrong type", source, 0, 0, "options");
  }
}

// The optional fields of a parameter entry: fixed, std_error (null or ≥ 0), its reason, ci95.
void read_uncertainty(const json& p, const std::string& source, const std::string& path,
                      ParameterEstimate& e) {
  if (p.contains("fixed")) e.fixed = core::json_bool(p["fixed"], source, path + "fixed");
  if (p.contains("std_error") && !p["std_error"].is_null()) {
    e.std_error = core::json_number(p["std_error"], source, path + "std_error");
    if (*e.std_error < 0.0) throw core::InputError("std_error must be null or >= 0", source, 0, 0, path + "std_error");
  }
  if (p.contains("std_error_reason"))
    e.std_error_reason = core::json_string(p["std_error_reason"], source, path + "std_error_reason");
  if (p.contains("ci95")) {
    if (!p["ci95"].is_array() || p["ci95"].size() != 2)
      throw core::InputError("expected [low, high]", source, 0, 0, path + "ci95");
    e.ci95_low = core::json_number(p["ci95"][0], source, path + "ci95[0]");
    e.ci95_high = core::json_number(p["ci95"][1], source, path + "ci95[1]");
  }
}

// One entry of "parameters" (path "parameters[i]."), checked against the model's spec.
ParameterEstimate read_parameter(const json& p, const core::ParameterSpec& spec,
                                 const std::string& source, const std::string& path) {
  const auto name = core::json_string(required(p, "name", source, path), source, path + "name");
  if (name != spec.name)
    throw core::InputError("expected parameter '" + spec.name + "', found '" + name + "'",
                           source, 0, 0, path + "name");
  ParameterEstimate e;
  e.value = core::json_number(required(p, "value", source, path), source, path + "value");
  // A positive scale must stay positive; a linear weight (a Prony modulus) may be exactly 0,
  // an inactive term held there by the non-negativity constraint.
  const bool must_be_positive = spec.transform == core::Transform::log && !spec.linear;
  if (!std::isfinite(e.value) || std::abs(e.value) > Card::kMaxMagnitude || e.value < spec.lower || e.value > spec.upper ||
      (must_be_positive && !(e.value > 0.0)))
    throw core::InputError("value " + core::short_number(e.value) + " outside the admissible range of " +
                               spec.name,
                           source, 0, 0, path + "value");
  read_uncertainty(p, source, path, e);
  return e;
}

// fit.data_window.damage_driver (data_window.hpp): one finite driver >= 0 per damage driver of the model.
void check_damage_drivers(const json& fit, const model::Model& m, const std::string& source) {
  const auto w = fit.find("data_window");
  if (w == fit.end() || !w->is_object() || !w->contains("damage_driver")) return;
  const json& d = w->at("damage_driver");
  model::TestCondition shear;  // any test: the count is the model's
  shear.orientation = "12";
  const std::size_t drivers = m.amplitude_dependent() ? m.damage_drivers(m.default_parameters().data(), shear).size() : 0;
  const auto bad = [](const json& x) { return !x.is_number() || !std::isfinite(x.get<double>()) || x.get<double>() < 0.0; };
  if (!d.is_array() || d.size() != drivers || std::any_of(d.begin(), d.end(), bad))
    throw core::InputError("expected " + std::to_string(drivers) + " finite number(s) >= 0, one per damage driver of model '" +
                               m.kind() + "'",
                           source, 0, 0, "fit.data_window.damage_driver");
}

}  // namespace

Card card_from_json(const json& j, const std::string& source) {
  if (!j.is_object()) throw core::InputError("a card must be a JSON object", source);
  Card card;
  const auto schema = core::json_string(required(j, "schema", source, ""), source, "schema");
  if (schema != Card::kSchema)
    throw core::InputError("unsupported schema '" + schema + "' (expected " + Card::kSchema + ")",
                           source, 0, 0, "schema");
  if (j.contains("name")) card.name = core::json_string(j.at("name"), source, "name");
  card.model_kind = core::json_string(required(j, "model", source, ""), source, "model");
  card.model_options = object_or_empty(j, "options", source);
  const model::ModelPtr m = model_of(card, source);
  if (!j.contains("parameters") || !j.at("parameters").is_array())
    throw core::InputError("missing parameter list", source, 0, 0, "parameters");
  const auto& list = j.at("parameters");
  const auto& specs = m->parameters();
  if (list.size() != specs.size())
    throw core::InputError("model '" + card.model_kind + "' with these options has " +
                               std::to_string(specs.size()) + " parameters, the card lists " +
                               std::to_string(list.size()),
                           source, 0, 0, "parameters");
  for (size_t i = 0; i < list.size(); ++i)
    card.parameters.push_back(
        read_parameter(list[i], specs[i], source, "parameters[" + std::to_string(i) + "]."));
  card.fit = object_or_empty(j, "fit", source);
  check_damage_drivers(card.fit, *m, source);
  card.provenance = object_or_empty(j, "provenance", source);
  return card;
}

Card load_card(const std::string& path) {
  return card_from_json(core::load_json(path), path);
}

void save_card(const std::string& path, const Card& card) {
  core::write_file_atomically(path, card_to_json(card).dump(2) + "\n");
}

}  // namespace fitlib::card
