#include "fitlib/card/card.hpp"

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

template <typename T>
T required(const json& j, const std::string& key, const std::string& source, const std::string& path) {
  if (!j.contains(key)) throw core::InputError("missing required key", source, 0, 0, path + key);
  try {
    return j.at(key).get<T>();
  } catch (const json::exception&) {
    throw core::InputError("wrong type", source, 0, 0, path + key);
  }
}

// An optional key: `fallback` when absent, InputError naming the key when of the wrong type.
template <typename T>
T optional(const json& j, const std::string& key, T fallback, const std::string& source,
           const std::string& path) {
  return j.contains(key) ? required<T>(j, key, source, path) : fallback;
}

}  // namespace

Card card_from_json(const json& j, const std::string& source) {
  if (!j.is_object()) throw core::InputError("a card must be a JSON object", source);
  Card card;
  const auto schema = required<std::string>(j, "schema", source, "");
  if (schema != Card::kSchema)
    throw core::InputError("unsupported schema '" + schema + "' (expected " + Card::kSchema + ")",
                           source, 0, 0, "schema");
  card.name = optional<std::string>(j, "name", "", source, "");
  card.model_kind = required<std::string>(j, "model", source, "");
  card.model_options = j.value("options", json::object());
  model::ModelPtr m;
  try {
    m = card.model();
  } catch (const core::UsageError& e) {
    throw core::InputError(e.what(), source, 0, 0, "options");
  }
  if (!j.contains("parameters") || !j.at("parameters").is_array())
    throw core::InputError("missing parameter list", source, 0, 0, "parameters");
  const auto& list = j.at("parameters");
  const auto& specs = m->parameters();
  if (list.size() != specs.size())
    throw core::InputError("model '" + card.model_kind + "' with these options has " +
                               std::to_string(specs.size()) + " parameters, the card lists " +
                               std::to_string(list.size()),
                           source, 0, 0, "parameters");
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string path = "parameters[" + std::to_string(i) + "].";
    const auto name = required<std::string>(list[i], "name", source, path);
    if (name != specs[i].name)
      throw core::InputError("expected parameter '" + specs[i].name + "', found '" + name + "'",
                             source, 0, 0, path + "name");
    ParameterEstimate e;
    e.value = required<double>(list[i], "value", source, path);
    const auto& spec = specs[i];
    // A positive scale must stay positive; a linear weight (a Prony modulus) may be exactly 0,
    // an inactive term held there by the non-negativity constraint.
    const bool must_be_positive = spec.transform == core::Transform::log && !spec.linear;
    if (!std::isfinite(e.value) || e.value < spec.lower || e.value > spec.upper ||
        (must_be_positive && !(e.value > 0.0)))
      throw core::InputError("value " + std::to_string(e.value) + " outside the admissible range of " +
                                 spec.name,
                             source, 0, 0, path + "value");
    e.fixed = optional<bool>(list[i], "fixed", false, source, path);
    if (list[i].contains("std_error") && !list[i]["std_error"].is_null()) {
      const auto& se = list[i]["std_error"];
      if (!se.is_number() || !std::isfinite(se.get<double>()) || se.get<double>() < 0.0)
        throw core::InputError("std_error must be null or a finite number >= 0", source, 0, 0,
                               path + "std_error");
      e.std_error = se.get<double>();
    }
    e.std_error_reason = optional<std::string>(list[i], "std_error_reason", "", source, path);
    if (list[i].contains("ci95")) {
      const auto ci95 = required<std::vector<double>>(list[i], "ci95", source, path);
      if (ci95.size() != 2 || !std::isfinite(ci95[0]) || !std::isfinite(ci95[1]))
        throw core::InputError("ci95 must be [low, high] with finite numbers", source, 0, 0, path + "ci95");
      e.ci95_low = ci95[0];
      e.ci95_high = ci95[1];
    }
    card.parameters.push_back(e);
  }
  card.fit = j.value("fit", json::object());
  card.provenance = j.value("provenance", json::object());
  return card;
}

Card load_card(const std::string& path) {
  return card_from_json(core::parse_json(core::read_file(path), path), path);
}

void save_card(const std::string& path, const Card& card) {
  core::write_file_atomically(path, card_to_json(card).dump(2) + "\n");
}

}  // namespace fitlib::card
