// The one place that maps model names to implementations.
#include <algorithm>
#include <mutex>
#include <nlohmann/json.hpp>

#include "fitlib/core/error.hpp"
#include "fitlib/model/elastic.hpp"
#include "fitlib/model/fritzson.hpp"
#include "fitlib/model/hyperelastic.hpp"
#include "fitlib/model/linear.hpp"
#include "fitlib/model/model.hpp"

namespace fitlib::model {
namespace {

// Models registered at run time (register_model), in registration order.
struct Registered {
  std::mutex mutex;
  std::vector<std::pair<std::string, ModelFactory>> factories;
};
Registered& registered() {
  static Registered r;
  return r;
}

ModelFactory registered_factory(const std::string& kind) {
  std::lock_guard<std::mutex> lock(registered().mutex);
  for (const auto& [name, factory] : registered().factories)
    if (name == kind) return factory;
  return nullptr;
}

}  // namespace

ModelPtr make_model(const std::string& kind, const nlohmann::json& options) {
  if (is_linear_kind(kind)) return make_linear_model(kind, options);
  if (fritzson::is_fritzson_kind(kind)) return fritzson::make_fritzson_model(kind, options);
  if (is_elastic_kind(kind)) return make_elastic_model(kind, options);
  if (is_hyperelastic_kind(kind)) return make_hyperelastic_model(kind, options);
  if (is_visco_hyperelastic_kind(kind)) return make_visco_hyperelastic_model(options);
  if (const ModelFactory factory = registered_factory(kind)) return factory(options);
  std::string known;
  for (const auto& k : model_kinds()) known += (known.empty() ? "" : ", ") + k;
  throw core::UsageError("unknown model '" + kind + "' (known: " + known + ")");
}

std::vector<std::string> model_kinds() {
  std::vector<std::string> kinds = {"prony", "zener3", "retardation", "fractional-zener", "fritzson",
                                    "fritzson-iso", "elastic-iso", "elastic-ortho"};
  for (const auto& k : hyperelastic_kinds()) kinds.push_back(k);
  kinds.push_back("visco-hyperelastic");
  std::lock_guard<std::mutex> lock(registered().mutex);
  for (const auto& entry : registered().factories) kinds.push_back(entry.first);
  return kinds;
}

void register_model(const std::string& kind, ModelFactory factory) {
  const auto kinds = model_kinds();
  if (kind.empty() || std::find(kinds.begin(), kinds.end(), kind) != kinds.end())
    throw core::UsageError("register_model: the name '" + kind + "' is empty or taken");
  if (!factory) throw core::UsageError("register_model: '" + kind + "' has no factory");
  std::lock_guard<std::mutex> lock(registered().mutex);
  registered().factories.emplace_back(kind, std::move(factory));
}

}  // namespace fitlib::model
